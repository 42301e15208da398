#!/usr/bin/env python3
"""analyze.py RUNDIR NAME -> prints one JSON line with the per-run metrics.
Expects in RUNDIR: truth.nav, truth_effects.yaml, gnss.txt, out.nav, out_innovations.txt,
out_std.txt, nav.stderr, nav.rc, nav.wall, compare.json (written by run_all.sh)."""
import sys, os, re, json, math, bisect

run, name = sys.argv[1], sys.argv[2]
P = lambda f: os.path.join(run, f)
res = {"name": name}

def rd(f):
    try:
        return open(P(f)).read()
    except OSError:
        return ""

err = rd("nav.stderr")
res["rc"] = int(rd("nav.rc").strip() or -99)
res["wall_s"] = float(rd("nav.wall").strip() or "nan")
# --- summary-line parsing
m = re.search(r"IMU (?:stamps late by|latency) ([-\d.]+) \+- ([\d.]+) ms([^)]*\)?)", err)
res["lat_applied"] = bool(re.search(r"found from the turns, taken out|a lag, taken out", err))
res["lat_found_ms"] = float(m.group(1)) if m else None
res["lat_sig_ms"] = float(m.group(2)) if m else None
r = re.search(r"refined by the GNSS likelihood over IMU shifts \(\d+ filter passes\) to ([-\d.]+) \+- ([\d.]+) ms", err)
res["lat_refined"] = bool(r)
if r:  # the latency the run used: the turns' estimate refined by the GNSS likelihood over IMU shifts
    res["lat_turns_ms"] = [res["lat_found_ms"], res["lat_sig_ms"]]
    res["lat_found_ms"], res["lat_sig_ms"] = float(r.group(1)), float(r.group(2))
res["lat_text"] = (m.group(0) if m else (re.search(r"IMU stamps[^;)]*", err).group(0) if re.search(r"IMU stamps[^;)]*", err) else ""))
m = re.search(r"initial state: ([^\n]*)", err)
res["init"] = m.group(1).strip() if m else ""
res["aligned_again"] = "aligned again" in err
m = re.search(r"at ([\d.]+) s the IMU's accelerations were turned ([-\d.]+) deg", err)
res["realign"] = [float(m.group(1)), float(m.group(2))] if m else None
m = re.search(r"gate rejections (\d+)", err)
res["gate_rej"] = int(m.group(1)) if m else None
m = re.search(r"(\d+) GNSS fixes;", err)
res["fixes_in_window"] = int(m.group(1)) if m else None
m = re.search(r"IMU noise as installed: gyro ([\d.]+)x, accel ([\d.]+)x", err)
res["noise_scale"] = f"{float(m.group(1)):g}/{float(m.group(2)):g}" if m else None
m = re.search(r"(\d+) fixes down-weighted", err)
res["downweighted"] = int(m.group(1)) if m else None
res["summary"] = " | ".join(l.strip() for l in err.splitlines() if l.startswith("ldv nav") or "gate rejections" in l or "IMU noise" in l)

# --- truth effects
te = rd("truth_effects.yaml")
def effect(nm):
    m = re.search(r"\n  %s:\n    si: \[([^\]]*)\]" % re.escape(nm), te)
    return [float(x) for x in m.group(1).split(",")] if m else None
lat = effect("imu_latency")
res["lat_true_ms"] = lat[0] * 1000 if lat else 0.0
mnt = effect("vehicle_mounting")
res["mount_true_deg"] = [round(math.degrees(x), 1) for x in mnt] if mnt else [0, 0, 0]
m = re.search(r"gnss_outlier_events:[^\n]*\n((?:  - [^\n]*\n)*)", te)
res["outlier_events"] = [float(l.split("[")[1].split(",")[0]) for l in m.group(1).splitlines()] if m else []
m = re.search(r"shock_events:[^\n]*\n((?:  - [^\n]*\n)*)", te)
res["shock_events"] = [float(l.split("[")[1].split(",")[0]) for l in m.group(1).splitlines()] if m else []

# --- GNSS file
g = [l.split() for l in rd("gnss.txt").splitlines() if l.strip() and not l.startswith("#")]
res["fixes_total"] = len(g)
sig = [sum(float(r[i]) for r in g) / len(g) for i in (4, 5, 6)] if g else [float("nan")] * 3

# --- innovations
inn = [l.split() for l in rd("out_innovations.txt").splitlines() if l.strip() and not l.startswith("#")]
pos = [r for r in inn if r[1] == "gnss_position"]
acc = [r for r in pos if r[-1] == "1"]
res["fixes_processed"] = len(pos)
res["fixes_accepted"] = len(acc)
res["rejected_times"] = [float(r[0]) for r in pos if r[-1] != "1"]
outl = set(round(t, 2) for t in res["outlier_events"])
good = [r for r in pos if round(float(r[0]), 2) not in outl]
gacc = [r for r in good if r[-1] == "1"]
res["outliers_in_window"] = len(pos) - len(good)
res["outliers_rejected"] = sum(1 for r in pos if round(float(r[0]), 2) in outl and r[-1] != "1")
res["good_rejected_times"] = [float(r[0]) for r in good if r[-1] != "1"]
res["used_pct_good"] = 100.0 * len(gacc) / len(good) if good else None
nis = sorted(float(r[8]) for r in good)
res["median_nis_good"] = nis[len(nis) // 2] if nis else None
res["used_pct_total"] = 100.0 * len(acc) / len(g) if g else None
res["used_pct_processed"] = 100.0 * len(acc) / len(pos) if pos else None
def rms(rows, i):
    return math.sqrt(sum(float(r[i]) ** 2 for r in rows) / len(rows)) if rows else float("nan")
if pos:
    rn, re_, rdn = rms(pos, 2), rms(pos, 3), rms(pos, 4)
    hs = math.sqrt((sig[0] ** 2 + sig[1] ** 2) / 2)
    res["innov_rms_m"] = [round(rn, 4), round(re_, 4), round(rdn, 4)]
    res["innov_ratio_h"] = math.sqrt((rn ** 2 + re_ ** 2) / 2) / hs
    res["innov_ratio_d"] = rdn / sig[2]
    res["innov_ratio_h_acc"] = math.sqrt((rms(acc, 2) ** 2 + rms(acc, 3) ** 2) / 2) / hs
    res["innov_ratio_h_good"] = math.sqrt((rms(gacc, 2) ** 2 + rms(gacc, 3) ** 2) / 2) / hs
    res["innov_ratio_d_good"] = rms(gacc, 4) / sig[2]
    res["mean_nis"] = sum(float(r[8]) for r in pos) / len(pos)
    res["stated_sigma_m"] = [round(s, 4) for s in sig]

# The same ratios for the oracle run (run.sh: the datasheet config with the IMU noise as installed, the
# simulator's truth): what the physics allows with this IMU and GNSS rate, whatever the self-calibration does.
orc = [l.split() for l in rd("oracle_innovations.txt").splitlines() if l.strip() and not l.startswith("#")]
orc = [r for r in orc if r[1] == "gnss_position" and r[-1] == "1" and round(float(r[0]), 2) not in outl]
if orc and pos:
    res["oracle_innov_ratio_h_good"] = math.sqrt((rms(orc, 2) ** 2 + rms(orc, 3) ** 2) / 2) / hs
    res["oracle_innov_ratio_d_good"] = rms(orc, 4) / sig[2]

# --- compare (official horizontal RMS)
try:
    c = json.loads(rd("compare.json"))["components"]
    res["h_rms_m"] = math.hypot(c["east"]["rms"], c["north"]["rms"])
    res["d_rms_m"] = c["down"]["rms"]
except Exception:
    res["h_rms_m"] = None

# --- own time series vs truth: horizontal error (interpolated) and attitude error (rotation vector)
def load_nav(f, step=1):
    out = []
    try:
        with open(P(f)) as fh:
            for k, l in enumerate(fh):
                if k % step or not l.strip() or l.startswith("#"):
                    continue
                out.append([float(x) for x in l.split()[1:11]])
    except OSError:
        pass
    return out
tr = load_nav("truth.nav")
nv = load_nav("out.nav", 20)
R = 6378137.0
def dcm(r, p, y):
    r, p, y = map(math.radians, (r, p, y))
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cp * cy, -cr * sy + sr * sp * cy, sr * sy + cr * sp * cy],
            [cp * sy, cr * cy + sr * sp * sy, -sr * cy + cr * sp * sy],
            [-sp, sr * cp, cr * cp]]
def rotvec(A, B):  # rotation vector of A * B^T
    E = [[sum(A[i][k] * B[j][k] for k in range(3)) for j in range(3)] for i in range(3)]
    c = max(-1.0, min(1.0, (E[0][0] + E[1][1] + E[2][2] - 1) / 2))
    ang = math.acos(c)
    v = [E[2][1] - E[1][2], E[0][2] - E[2][0], E[1][0] - E[0][1]]
    s = math.sqrt(sum(x * x for x in v)) or 1e-12
    return [math.degrees(ang) * x / s for x in v], math.degrees(ang)
series = []
if tr and nv:
    tt = [r[0] for r in tr]
    for r in nv:
        t = r[0]
        i = bisect.bisect_left(tt, t)
        if i <= 0 or i >= len(tt):
            continue
        a, b = tr[i - 1], tr[i]
        w = (t - a[0]) / (b[0] - a[0])
        lat_t = a[1] + w * (b[1] - a[1]); lon_t = a[2] + w * (b[2] - a[2])
        dn = math.radians(r[1] - lat_t) * R
        de = math.radians(r[2] - lon_t) * R * math.cos(math.radians(lat_t))
        near = a if w < 0.5 else b
        phi, ang = rotvec(dcm(r[7], r[8], r[9]), dcm(near[7], near[8], near[9]))
        series.append((t, math.hypot(dn, de), phi, ang))
std = [l.split() for l in rd("out_std.txt").splitlines() if l.strip() and not l.startswith("#")]
if series:
    t0 = series[0][0]
    res["t_start"] = t0
    res["h_max_m"], res["h_max_t"] = max((s[1], s[0] - t0) for s in series)
    # 50-s window RMS of horizontal error and attitude error
    win = {}
    for s in series:
        k = int((s[0] - t0) // 50)
        win.setdefault(k, []).append(s)
    res["h_rms_win"] = [round(math.sqrt(sum(x[1] ** 2 for x in v) / len(v)), 3) for k, v in sorted(win.items())]
    res["att_err_win"] = [round(max(x[3] for x in v), 2) for k, v in sorted(win.items())]
    res["att_err_end_deg"] = round(series[-1][3], 3)
    res["att_err_max_after60_deg"] = round(max([s[3] for s in series if s[0] - t0 > 60] or [float("nan")]), 3)
    res["att_phi_end_deg"] = [round(x, 3) for x in series[-1][2]]
    if std:
        sa = [float(x) for x in std[-1][8:11]]
        res["att_std_end_deg"] = sa
        res["mount_ok_3sig"] = all(abs(p) <= 3 * s for p, s in zip(series[-1][2], sa))
        # fraction of time after 60 s where the error is within 3 sigma (std rows nearest)
        st = [float(r[1]) for r in std]
        ok = n = 0
        for s in series:
            if s[0] - t0 <= 60:
                continue
            j = min(bisect.bisect_left(st, s[0]), len(st) - 1)
            sj = [float(x) for x in std[j][8:11]]
            n += 1
            ok += all(abs(p) <= 3 * q for p, q in zip(s[2], sj))
        res["mount_ok_frac"] = round(ok / n, 3) if n else None
if res["lat_found_ms"] is not None and res["lat_sig_ms"]:
    res["lat_z"] = (res["lat_found_ms"] - res["lat_true_ms"]) / res["lat_sig_ms"]
    res["lat_ok_3sig"] = abs(res["lat_z"]) <= 3
else:
    res["lat_z"] = None
    res["lat_ok_3sig"] = res["lat_true_ms"] < 5  # nothing found: OK only if nothing was injected
print(json.dumps(res))
