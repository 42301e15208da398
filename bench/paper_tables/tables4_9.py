#!/usr/bin/env python3
"""Formats the paper's Tables 4-9 beside ldv allan's JSON (bench/paper_tables/tables4_9.sh).
usage: tables4_9.py OUT_DIR PAPER_TABLES.yaml SEED"""
import json
import math
import re
import sys

import yaml

out_dir, paper_path, seed = sys.argv[1], sys.argv[2], sys.argv[3]
paper = yaml.safe_load(open(paper_path))
records = paper["experiment"]["allan_records"]

# (table key in the YAML, IMU name in the YAML, sensor, the ldv sim grades whose records it is compared with)
tables = [("table4_hg1700_accel", "HG1700", "accel", ["hg1700-paper"]),
          ("table5_hg1700_gyro", "HG1700", "gyro", ["hg1700-paper"]),
          ("table6_hg1900_accel", "HG1900", "accel", ["hg1900-paper"]),
          ("table7_hg1900_gyro", "HG1900", "gyro", ["hg1900-paper"]),
          ("table8_3dm_gx2_accel", "3DM-GX2", "accel", ["3dm-gx2-paper"]),
          ("table9_3dm_gx2_gyro", "3DM-GX2", "gyro", ["3dm-gx2-paper", "3dm-gx2-paper-q-arcsec"])]
TERMS = ["Q", "N", "B", "K", "R"]

# SI (ldv allan's JSON: rad, rad/sqrt(s), rad/s, rad/s/sqrt(s), rad/s^2; m/s, m/s/sqrt(s), m/s^2, ...) to the unit
# a YAML key names (its suffix), converted here rather than taken from the JSON's paper_units, so the tool's own
# conversion is checked on the way (check_paper_units below).
DEG = math.pi / 180.0
TO_PAPER = {"arcsec": 3600.0 / DEG, "deg": 1.0 / DEG, "deg_sqrt_h": 60.0 / DEG, "deg_h": 3600.0 / DEG,
            "deg_h_sqrt_h": 3600.0 * 60.0 / DEG, "deg_h2": 3600.0 ** 2 / DEG,
            "m_h": 3600.0, "mps_sqrt_h": 60.0, "mps_h": 3600.0, "mps_h_sqrt_h": 3600.0 * 60.0, "mps_h2": 3600.0 ** 2}
UNIT_TEXT = {"arcsec": "arcsec", "deg": "deg", "deg_sqrt_h": "deg/sqrt(h)", "deg_h": "deg/h",
             "deg_h_sqrt_h": "deg/h/sqrt(h)", "deg_h2": "deg/h^2", "m_h": "m/h", "mps_sqrt_h": "m/s/sqrt(h)",
             "mps_h": "m/s/h", "mps_h_sqrt_h": "m/s/h/sqrt(h)", "mps_h2": "m/s/h^2"}
# The unit of a term the paper does not print for that sensor (the family's usual one).
DEFAULT_UNIT = {"gyro": {"Q": "arcsec", "N": "deg_sqrt_h", "B": "deg_h", "K": "deg_h_sqrt_h", "R": "deg_h2"},
                "accel": {"Q": "m_h", "N": "mps_sqrt_h", "B": "mps_h", "K": "mps_h_sqrt_h", "R": "mps_h2"}}
# ldv allan's unit strings for the same units (its JSON paper_units), to check its conversion.
TOOL_UNIT = {"arcsec": "arcsec", "deg_sqrt_h": "deg/sqrt(h)", "deg_h": "deg/h", "deg_h_sqrt_h": "deg/h/sqrt(h)",
             "deg_h2": "deg/h/h", "m_h": "m/h", "mps_sqrt_h": "m/s/sqrt(h)", "mps_h": "m/s/h",
             "mps_h_sqrt_h": "m/s/h/sqrt(h)", "mps_h2": "m/s/h^2"}
unit_problems = []


def fmt(x):
    if x is None:
        return "-"
    if x == 0:
        return "0"
    return f"{x:.4g}" if abs(x) < 10000 else f"{x:.0f}"


def paper_terms(table):
    """{term: (unit suffix, [x, y, z, avg])} and the time constant, from the YAML keys (e.g. B_mps_h)."""
    terms, time_constant, notes = {}, None, {}
    for key, value in table.items():
        if key == "B_time_constant_s":
            time_constant = value
        elif key.endswith("_note"):
            notes[key.split("_")[0]] = value
        else:
            m = re.fullmatch(r"([QNBKR])_(.+)", key)
            if not m or m.group(2) not in TO_PAPER:
                raise SystemExit(f"{paper_path}: unknown key {key}")
            terms[m.group(1)] = (m.group(2), value)
    return terms, time_constant, notes


def load(grade, suffix=""):
    run = json.load(open(f"{out_dir}/{grade}{suffix}.json"))
    return {c["name"]: c for c in run["channels"]}


def check_paper_units(channel, term, unit):
    """ldv allan's own paper-unit value against this script's conversion of its SI value."""
    pu = channel.get("paper_units", {}).get(term)
    if pu is None or unit not in TOOL_UNIT:
        return
    ours = channel[term] * TO_PAPER[unit]
    if pu["unit"] != TOOL_UNIT[unit] or abs(pu["value"] - ours) > 1e-9 * max(abs(ours), 1e-30) + 1e-15:
        unit_problems.append(f"{channel['name']} {term}: ldv allan prints {pu['value']} {pu['unit']}, "
                             f"its SI value gives {ours} {UNIT_TEXT[unit]}")


def cell(ours, lo, hi, theirs, resolved, interval=True):
    text = fmt(ours)
    if interval and lo is not None:
        text += f" [{fmt(lo)}, {fmt(hi)}]"
    if not resolved:
        text += " n.r."
    if theirs is None:
        return text + " / -"
    ratio = ours / theirs if theirs > 0 else float("inf")
    outside = interval and lo is not None and not (lo <= theirs <= hi)
    return f"{text} / {fmt(theirs)} (**{ratio:.2g}**{', out' if outside else ''})"


def average(values, paper_values):
    """The paper's average column: the mean over the axes it prints a value for."""
    use = [v for v, p in zip(values, paper_values[:3]) if p is not None] if paper_values else values
    return sum(use) / len(use) if use else None


def time_constant_cell(ch, theirs):
    """The Gauss-Markov T with its 95 % interval from the profile likelihood (the JSON's B_T_s_lo, B_T_s_hi)."""
    t, lo, hi = ch["B_T_s"], ch.get("B_T_s_lo", 0), ch.get("B_T_s_hi", 0)
    if t > 0 and hi > 0:
        return cell(t, lo, hi, theirs, ch["B_resolved"])
    return cell(t, None, None, theirs, ch["B_resolved"], False)


def term_row(label, chans, term, unit, printed, note=None):
    k = TO_PAPER[unit]
    cells = []
    for i, ch in enumerate(chans):
        check_paper_units(ch, term, unit)
        theirs = printed[i] if printed else None
        cells.append(cell(ch[term] * k, ch[f"{term}_lo"] * k, ch[f"{term}_hi"] * k, theirs, ch[f"{term}_resolved"]))
    cells.append(cell(average([ch[term] * k for ch in chans], printed), None, None, printed[3] if printed else None,
                      True, False))
    if note:
        cells[-1] += f" (paper: \"{note}\")"
    return (label, cells)


def table_rows(sensor, auto, gm, terms, time_constant, notes):
    """Rows of one table: the default run (bias model by AIC), then the paper's Gauss-Markov forced."""
    rows = []
    unit_of = {t: terms.get(t, (DEFAULT_UNIT[sensor][t], None)) for t in TERMS}
    for term in TERMS:
        unit, printed = unit_of[term]
        label = f"{term} [{UNIT_TEXT[unit]}]" + (" (model by AIC)" if term == "B" else "")
        rows.append(term_row(label, auto, term, unit, printed, notes.get(term)))
        if term == "B":
            cells = [time_constant_cell(ch, time_constant[i] if time_constant else None)
                     if ch["B_model"] == "gauss_markov"
                     else "flat" + (f" / {fmt(time_constant[i])}" if time_constant else "")
                     for i, ch in enumerate(auto)]
            cells.append(cell(average([ch["B_T_s"] for ch in auto], time_constant), None, None, time_constant[3], True,
                              False) if time_constant and all(ch["B_model"] == "gauss_markov" for ch in auto) else "-")
            rows.append(("T [s] (of the GM, when chosen)", cells))
            sel = []
            for ch in auto:
                s = ch["bias_model_selection"]
                chosen = "GM" if s["chosen"] == "gauss_markov" else s["chosen"]
                stands = "" if s.get("gauss_markov_stands_out", True) else ", GM does not stand out"
                sel.append(f"{chosen} (LR {s.get('likelihood_ratio', 0):.3g}{stands})")
            rows.append(("bias model chosen by AIC (LR = 2 (lnL GM - lnL flat); GM when LR > 2 and it stands out)",
                         sel + [""]))
    for term in ("N", "B", "K"):
        unit, printed = unit_of[term]
        rows.append(term_row(f"{term} [{UNIT_TEXT[unit]}] `--gauss-markov`", gm, term, unit, printed))
        if term == "B":
            cells = [time_constant_cell(ch, time_constant[i] if time_constant else None) for i, ch in enumerate(gm)]
            cells.append(cell(average([ch["B_T_s"] for ch in gm], time_constant), None, None, time_constant[3], True,
                              False) if time_constant else "-")
            rows.append(("T [s] `--gauss-markov`", cells))
    if "B" in terms and "K" in terms and time_constant:
        # How far the paper's random walk stands above its Gauss-Markov where the GM is most visible (its Allan
        # peak, 0.6174 sigma at 1.893 T): K sqrt(tau/3) there over 0.6174 sigma (K per sqrt(s): / 60).
        buried = [terms["K"][1][i] / 60.0 * math.sqrt(1.893 * time_constant[i] / 3.0) / (0.6174 * terms["B"][1][i])
                  for i in range(3)]
        rows.append(("paper's K / its GM at the GM's Allan peak (1.893 T)", [f"{b:.2f}" for b in buried] + [""]))
    info = []
    for ch in auto:
        ri = ch.get("record_information", {}).get("relative_sd", {})
        info.append(", ".join(f"{t} {100 * ri[t]:.2g} %" for t in ("N", "B", "K") if ri.get(t)) or "-")
    rows.append(("Cramer-Rao sd of the default fit's terms in this record", info + [""]))
    return rows


print("# The paper's Tables 4-9 regenerated by simulation\n")
print("Generated by `bench/paper_tables/tables4_9.sh` (simulator seed %s): `ldv sim --scenario static` with the "
      "paper's grades (`hg1700-paper`, `hg1900-paper`, `3dm-gx2-paper`, `3dm-gx2-paper-q-arcsec`: Tables 4-9 per axis as "
      "printed, absent terms absent, Table 3's turn-on bias, scale and non-orthogonality) for the paper's record "
      "lengths and rates (%s), each record analysed by `ldv allan` as it runs by default (Q from the Allan-curve fit; "
      "N, B, K, R by the likelihood of the raw data; the bias model, flat B or Gauss-Markov sigma and T, chosen per "
      "axis by AIC) and again with `--gauss-markov` (the paper's bias model, forced). Each cell is **ours [95 %% "
      "interval] / paper (ratio)**; `n.r.` = ldv allan does not call the term resolved; `out` = the paper's value, "
      "which is the simulated truth, lies outside ours 95 %% interval; `-` = the paper prints no value (the term is "
      "absent from the simulated sensor). The avg column is the mean over the axes the paper prints (as its own "
      "average column). The paper's numbers are read from `../shared/data/paper/geo_ldv_tables.yaml`, in its "
      "units.\n" % (seed, "; ".join(f"{imu} {r['duration_h']} h at {r['rate_hz']} Hz" for imu, r in records.items())))
arcsec_same_accel = None
for key, imu, sensor, grades in tables:
    terms, time_constant, notes = paper_terms(paper[key])
    number = re.match(r"table(\d+)", key).group(1)
    for grade in grades:
        auto, gm = load(grade), load(grade, ".gm")
        auto = [auto[f"{sensor}_{a}"] for a in "xyz"]
        gm = [gm[f"{sensor}_{a}"] for a in "xyz"]
        grade_terms = dict(terms)
        if grade.endswith("-q-arcsec"):
            # The second reading of Table 9: the printed Q numbers taken as arcsec (ldv sim's grade of that name).
            grade_terms["Q"] = ("arcsec", terms["Q"][1])
        first = auto[0]
        hours = first["samples"] * first["tau0_s"] / 3600.0
        print(f"## Table {number}: {imu} {'gyro' if sensor == 'gyro' else 'accelerometer'} (`{grade}`, "
              f"{hours:.3g} h at {1.0 / first['tau0_s']:.3g} Hz)\n")
        if grade.endswith("-q-arcsec"):
            print("The printed Q (%s deg) read as arcsec, as this grade simulates it; every other term as printed.\n"
                  % ", ".join(fmt(v) for v in terms["Q"][1][:3]))
        print("| term | X | Y | Z | avg |")
        print("|---|---|---|---|---|")
        for label, cells in table_rows(sensor, auto, gm, grade_terms, time_constant, notes):
            print(f"| {label} | " + " | ".join(cells) + " |")
        print()
    # The paper's average column against the mean of its own axes (the avg ratios above are against the printed one).
    printed = dict(terms)
    if time_constant:
        printed["T"] = ("s", time_constant)
    odd = []
    for term, (unit, values) in printed.items():
        axes = [v for v in values[:3] if v is not None]
        mean = sum(axes) / len(axes)
        if abs(values[3] - mean) > 0.01 * abs(mean):
            odd.append(f"{term} prints {fmt(values[3])}, its axes average {fmt(mean)}")
    if odd:
        print(f"The paper's avg column of Table {number} against the mean of its own axes: " + "; ".join(odd) + ".\n")
    if key == "table8_3dm_gx2_accel":
        # The two 3DM-GX2 grades differ only in the gyro Q: the accelerometer records (own random streams) must
        # give the same Table 8.
        other = load("3dm-gx2-paper-q-arcsec")
        arcsec_same_accel = all(other[f"accel_{a}"][t] == load("3dm-gx2-paper")[f"accel_{a}"][t]
                                for a in "xyz" for t in TERMS)
        print("The `3dm-gx2-paper-q-arcsec` record's accelerometer gives %s Table 8 (the two grades differ only in the "
              "gyro Q).\n" % ("exactly the same" if arcsec_same_accel else "**a different**"))
if unit_problems:
    print("**ldv allan's paper_units disagree with its SI values:** " + "; ".join(unit_problems) + "\n")
else:
    print("ldv allan's own paper-unit values (JSON `paper_units`) agree with this script's conversion of its SI "
          "values for every term above.\n")
