#!/usr/bin/env bash
# Writes the seed corpus of the fuzz targets into tests/fuzz/corpus/ (kept in the repository): short valid inputs
# of every format, made by the project's own simulator (`ldv sim`) and by the formats' specifications (UBX, the
# 3DM-GX2 records, the LCM log layout), each behind the target's selector bytes (see each fuzz_*.cpp).
# Run after a build: tests/fuzz/make_seed_corpus.sh build/bin/ldv
set -euo pipefail
ldv="$1"
here="$(cd "$(dirname "$0")" && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$ldv" sim --grade 3dm-gx2-typical --duration 4 --gnss-rate 5 --gnss-velocity --odometer --seed 3 --quiet --out "$tmp/sim"
"$ldv" sim --grade hg1700-typical --duration 4 --gnss-rate 5 --seed 4 --quiet --out "$tmp/sim7"
python3 - "$tmp" "$here/corpus" "$here/../../deploy/config" <<'PY'
import os, struct, sys, random
tmp, corpus, deploy = sys.argv[1], sys.argv[2], sys.argv[3]
def put(target, name, data):
    d = os.path.join(corpus, target); os.makedirs(d, exist_ok=True)
    open(os.path.join(d, name), "wb").write(data)
def head(path, lines):
    with open(path, "rb") as f: return b"".join(f.readlines()[:lines])
sim, sim7 = os.path.join(tmp, "sim"), os.path.join(tmp, "sim7")
# fuzz_kfgins_text: selector 0 imu.txt, 1 gnss.txt, 2 .nav, 3 odo.txt
put("fuzz_kfgins_text", "imu_txt", b"\x00" + head(f"{sim}/imu.txt", 40))
put("fuzz_kfgins_text", "gnss_txt_13", b"\x01" + head(f"{sim}/gnss.txt", 12))
put("fuzz_kfgins_text", "gnss_txt_7", b"\x01" + head(f"{sim7}/gnss.txt", 12))
put("fuzz_kfgins_text", "truth_nav", b"\x02" + head(f"{sim}/truth.nav", 20))
put("fuzz_kfgins_text", "odo_txt", b"\x03" + head(f"{sim}/odo.txt", 30))
# fuzz_rtklib_files: selector 0 .pos; 1 tagged CSV (bytes 1-2 the tag's length, the tag, the CSV)
put("fuzz_rtklib_files", "gnss_pos", b"\x00" + head(f"{sim}/gnss.pos", 30))
tag = bytearray(b"TIMETAG RTKLIB EX".ljust(60, b"\0"))
tag += struct.pack("<II", 0, 315964800 + 1400000000) + struct.pack("<d", 0.25)
csv = b""
for i in range(40):
    csv += b"0.01,-0.02,1.0,0.5,-0.5,0.1,%d\n" % (1000 + 10 * i)
    tag += struct.pack("<II", 10 * i + 2, len(csv))
put("fuzz_rtklib_files", "tagged_csv", b"\x01" + struct.pack("<H", len(tag)) + bytes(tag) + csv)
# fuzz_user_tables: selector bits (1 row clock, 2 IMU, 4 columns by name, 8 increments / ECEF, 16 interval means /
# std and quality columns, 32 a UTC date-time column, 64 a date and a time of day in two columns), then the data file
put("fuzz_user_tables", "imu_named_csv", b"\x06t,gx,gy,gz,ax,ay,az\n0,0.1,0.2,0.3,0,0,1\n10,0.1,0.2,0.3,0,0,1\n"
    b"20,0.2,0.2,0.3,0,0.01,1\n")
put("fuzz_user_tables", "imu_rows_semicolon", b"\x13sep=;\n\"t\";\"a\";\"b\";\"c\";\"d\";\"e\";\"f\"\n"
    b"0;0,1;0,2;0,3;0;0;1\n10;0,1;0,2;0,3;0;0;1\n")
put("fuzz_user_tables", "gnss_named_ws", b"\x04% t lat lon h\n0 40.1 -105.1 1600\n200 40.1 -105.1 1600\n"
    b"200 40.1 -105.1 1600\n400 40.2 -105.2 1601\n")
# 32 (0x20): column 1 a UTC date-time; 64 (0x40): columns 8 and 9 a GPST date and time of day
put("fuzz_user_tables", "imu_utc_date_time", b"\x22stamp,gx,gy,gz,ax,ay,az\n2024-08-27T17:30:00.00Z,0,0,0,0,0,-1\n"
    b"2024-08-27T17:30:00.01Z,0,0,0,0,0,-1\n2024-08-27 19:30:00.02+02:00,0,0,0,0,0,-1\n")
put("fuzz_user_tables", "gnss_date_and_time_fields", b"\x40t lat lon h s1 s2 s3 date time\n"
    b"0 40.1 -105.1 1600 0 0 0 2024/08/27 17:30:00.0\n1 40.1 -105.1 1600 0 0 0 2024/08/27 17:30:00.2\n")
put("fuzz_user_tables", "gnss_ecef_std_quality", b"\x18t,x,y,z,sx,sy,sz,q\n"
    b"0,-1283000.1,-4720000.2,4079000.3,0.01,0.01,0.02,4\n200,-1283000.2,-4720000.2,4079000.3,0.01,0.01,0.02,5\n")
# fuzz_gnss_stream: selector (0 auto, 1 nmea, 2 ubx, 3 rtklib), chunk size, bytes
nmea = head(f"{sim}/gnss.nmea", 40)
put("fuzz_gnss_stream", "nmea_auto", b"\x00\x10" + nmea)
put("fuzz_gnss_stream", "nmea", b"\x01\x05" + nmea)
put("fuzz_gnss_stream", "rtklib", b"\x03\x20" + head(f"{sim}/gnss.pos", 30))
def ubx(cls, mid, payload):
    body = bytes([cls, mid]) + struct.pack("<H", len(payload)) + payload
    a = b = 0
    for x in body: a = (a + x) & 0xFF; b = (b + a) & 0xFF
    return b"\xb5\x62" + body + bytes([a, b])
def nav_pvt(itow_ms, lat, lon, h_mm):
    p = bytearray(92)
    struct.pack_into("<I", p, 0, itow_ms)
    struct.pack_into("<HBBBBB", p, 4, 2024, 6, 24, 8, 20, 0)
    p[11] = 0x37  # valid date, time, fully resolved
    p[20] = 3; p[21] = 0x01 | 0x80  # 3D fix, gnssFixOK, carrier fixed
    p[23] = 20
    struct.pack_into("<iiii", p, 24, int(lon * 1e7), int(lat * 1e7), h_mm, h_mm - 40000)
    struct.pack_into("<II", p, 40, 14, 20)  # hAcc, vAcc [mm]
    struct.pack_into("<iii", p, 48, 100, -50, 3)
    struct.pack_into("<I", p, 68, 30)  # sAcc [mm/s]
    return ubx(0x01, 0x07, bytes(p))
stream = b"".join(nav_pvt(115218000 + 200 * k, 35.1 + 1e-7 * k, 136.9, 104800) for k in range(8))
put("fuzz_gnss_stream", "ubx_nav_pvt", b"\x02\x11" + stream)
put("fuzz_gnss_stream", "ubx_auto_mixed", b"\x00\x07" + stream[:200] + nmea[:400] + stream[200:])
# fuzz_imu_device: selector (0 time-stamp unit, 1 3DM-GX2), chunk size, bytes
with open(f"{sim}/imu_device.bin", "rb") as f: put("fuzz_imu_device", "tsu", b"\x00\x0d" + f.read(3000))
gx2 = b""
for k in range(40):
    rec = bytes([0xC3]) + struct.pack(">6f", 1e-5, -2e-5, 3e-6, 0.0, 0.0, -0.00102) + struct.pack(">I", 196608 * k)
    gx2 += rec + struct.pack(">H", sum(rec) & 0xFFFF)
put("fuzz_imu_device", "gx2_c3", b"\x01\x1f" + gx2)
# fuzz_lcm_log: the event layout (big-endian): sync, event number, time [us], channel length, data length
log = b""
rnd = random.Random(7)
for k in range(12):
    ch = [b"IMU", b"GNSS_SOLUTION", b"STATUS_FUSION"][k % 3]
    data = bytes(rnd.randrange(256) for _ in range(40 + 7 * k))
    log += struct.pack(">IqqII", 0xEDA1DA01, k, 1700000000000000 + 5000 * k, len(ch), len(data)) + ch + data
put("fuzz_lcm_log", "events", log)
put("fuzz_lcm_log", "cut_last", log[:-9])
# fuzz_yaml_configs: selector 0 KF-GINS (+ ldv:), 1 imu_acq, 2 gnss_link
put("fuzz_yaml_configs", "kfgins", b"\x00" + open(f"{sim}/kfgins.yaml", "rb").read())
put("fuzz_yaml_configs", "imu_acq", b"\x01" + open(f"{deploy}/imu_acq.yaml", "rb").read())
put("fuzz_yaml_configs", "gnss_link", b"\x02" + open(f"{deploy}/gnss_link.yaml", "rb").read())
# fuzz_bus_gate: scripts of (selector, value) pairs; empty = the clean stream
put("fuzz_bus_gate", "clean", b"")
for seed in range(4):
    r = random.Random(seed)
    put("fuzz_bus_gate", f"random_{seed}", bytes(r.randrange(256) for _ in range(600)))
PY
echo "seed corpus written to $here/corpus"
