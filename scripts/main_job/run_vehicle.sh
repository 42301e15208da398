#!/usr/bin/env bash
# The vehicle side of the main job, run inside a private network namespace (netns_run.sh):
# the simulated devices on pseudo-terminals, the four services, two lcm-loggers; TSPI printed.
set -euo pipefail
out="$1"; bin="$2"
cfg="$out/config"; mkdir -p "$cfg"
bus="udpm://239.255.76.67:7667?ttl=0"
tspi_group=239.255.77.1; tspi_port=7668

cat > "$cfg/imu_acq.yaml" <<YAML
bus_url: "$bus"
input: {type: serial, serial: {device: $out/imu_tty, baud: 460800}}
protocol: tsu
tsu: {counter_hz: 10.0e6}
sample_rate_hz: 200
pps: {source: device, label_refers: auto}
YAML
cat > "$cfg/gnss_link.yaml" <<YAML
bus_url: "$bus"
input: {type: serial, serial: {device: $out/gnss_tty, baud: 115200}}
protocol: nmea
gps_minus_utc_s: 18
YAML
cat > "$cfg/fusion.yaml" <<YAML
bus_url: "$bus"
kfgins_config: $out/sim/kfgins.yaml
history_s: 3.0
state_file: $out/fusion_warm_state.yaml
YAML
cat > "$cfg/tspi_pub.yaml" <<YAML
bus_url: "$bus"
tspi: {rate_hz: 20, group: $tspi_group, port: $tspi_port, ttl: 1, channel: TSPI, print: true}
YAML

pids=()
cleanup() { for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT

lcm-logger --lcm-url="$bus" -q -f "$out/vehicle.lcmlog" & pids+=($!)
lcm-logger --lcm-url="udpm://$tspi_group:$tspi_port?ttl=1" -q -f "$out/tspi.lcmlog" & pids+=($!)
"$bin/ldv" drive "$out/sim" --imu-link "$out/imu_tty" --gnss-link "$out/gnss_tty" --start-delay 2 & drive=$!
sleep 0.5
"$bin/imu_acq" --config "$cfg/imu_acq.yaml" 2> "$out/imu_acq.log" & pids+=($!)
"$bin/gnss_link" --config "$cfg/gnss_link.yaml" 2> "$out/gnss_link.log" & pids+=($!)
"$bin/fusion" --config "$cfg/fusion.yaml" 2> "$out/fusion.log" & pids+=($!)
"$bin/tspi_pub" --config "$cfg/tspi_pub.yaml" 2> "$out/tspi_pub.log" & pids+=($!)
wait "$drive"
sleep 1.5
