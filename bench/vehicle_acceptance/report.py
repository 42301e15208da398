#!/usr/bin/env python3
"""report.py OUT_DIR: results.jsonl (+ runs/*/diag.json) -> results_table.md (table + per-criterion pass counts)."""
import json, os, sys
A = sys.argv[1]
rows = [json.loads(l) for l in open(f"{A}/results.jsonl")]
order = lambda r: (r["name"].startswith("single"), r["name"])
rows.sort(key=order)
T = ["| run | used% seen (all/ex-outl) | gate rej | outl rej/in | realign@s | hRMS m | hMax m@s | innov/σ H,D (oracle) | noise× g/a | IMU lat found±σ / true ms (z) | att err end° (3σ) / t-frac in 3σ | nav s | diagnose --iterate |",
     "|" + "---|" * 13]
fails = {k: [] for k in ("C1 used>=98%", "C2 innov<=1.5σ", "C2' innov<=1.1x oracle", "C3a latency 3σ", "C3b mounting 3σ", "C4 diag consistent")}
for r in rows:
    d = f"{A}/runs/{r['name']}"
    diag = "n/a"
    if os.path.exists(f"{d}/diag.json"):
        j = json.load(open(f"{d}/diag.json"))
        parts = []
        for s in j["steps"][1:]:
            e = s.get("estimate") or []; sg = s.get("sigma") or []
            if s["added"] == "time_offset": est = f"{e[0]*1e3:.0f}±{sg[0]*1e3:.0f}ms"
            elif s["added"] == "imu_noise": est = "x" + "/".join(f"{x:.0f}" for x in e)
            else: est = "[" + ",".join(f"{x:.2f}" for x in e) + "]±[" + ",".join(f"{x:.2f}" for x in sg) + "]m"
            parts.append(f"{s['added']} {est} {s['accepted_fixes']}/{s['total_fixes']} NIS{s['mean_nis']:.2f}")
        diag = ("**CONS** " if j["consistent"] else "**NOT cons** ") + "; ".join(parts)
        if not j["consistent"]: fails["C4 diag consistent"].append((r["name"], "not consistent"))
    lat = (f"{r['lat_found_ms']:.0f}±{r['lat_sig_ms']:.0f} / {r['lat_true_ms']:.0f} ({r['lat_z']:+.1f}{', applied' if r['lat_applied'] else ''}"
           f"{', refined' if r.get('lat_refined') else ''})")
    rl = f"{r['realign'][0]-345600:.0f}" if r["realign"] else ""
    orc = f" ({r['oracle_innov_ratio_h_good']:.1f},{r['oracle_innov_ratio_d_good']:.1f})" if "oracle_innov_ratio_h_good" in r else ""
    T.append(f"| {r['name']} | {r['used_pct_processed']:.1f}/{r['used_pct_good']:.1f} | {r['gate_rej']} | {r['outliers_rejected']}/{r['outliers_in_window']} | {rl} | {r['h_rms_m']:.3f} | "
             f"{r['h_max_m']:.2f}@{r['h_max_t']+r['t_start']-345600:.0f} | {r['innov_ratio_h_good']:.1f},{r['innov_ratio_d_good']:.1f}{orc} | {r['noise_scale']} | {lat} | "
             f"{r['att_err_end_deg']:.2f} ({'ok' if r['mount_ok_3sig'] else 'NO'}) / {r['mount_ok_frac']:.2f} | {r['wall_s']:.2f} | {diag} |")
    if r["used_pct_good"] < 98: fails["C1 used>=98%"].append((r["name"], f"{r['used_pct_good']:.1f}%"))
    w = max(r["innov_ratio_h_good"], r["innov_ratio_d_good"])
    if w > 1.5: fails["C2 innov<=1.5σ"].append((r["name"], f"{w:.1f}x"))
    if "oracle_innov_ratio_h_good" in r:  # against what the IMU as installed allows (the oracle's ratio)
        wo = max(r["oracle_innov_ratio_h_good"], r["oracle_innov_ratio_d_good"])
        if w > 1.1 * wo: fails["C2' innov<=1.1x oracle"].append((r["name"], f"{w:.1f}x vs {wo:.1f}x"))
    if abs(r["lat_z"]) > 3 or (not r["lat_applied"] and r["lat_true_ms"] > 30):
        fails["C3a latency 3σ"].append((r["name"], f"z={r['lat_z']:+.0f}{'' if r['lat_applied'] else ' not applied'}"))
    if not r["mount_ok_3sig"]: fails["C3b mounting 3σ"].append((r["name"], f"{r['att_err_end_deg']:.1f}°"))
T.append("")
for k, v in fails.items():
    T.append(f"- {k}: {len(v)} fail — " + ", ".join(f"{n} {x}" for n, x in v))
open(f"{A}/results_table.md", "w").write("\n".join(T) + "\n")
print("\n".join(T))
