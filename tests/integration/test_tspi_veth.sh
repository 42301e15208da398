#!/usr/bin/env bash
# A remote TSPI subscriber (DESIGN.md section 8): two network namespaces joined by a veth pair, as
# the vehicle computer and a remote user on the vehicle network. Namespace A runs tspi_pub (fed by a
# NAV publisher on A's loopback vehicle bus) with TSPI routed onto the veth; namespace B subscribes.
#   TTL 1: B receives every TSPI, in sequence.   TTL 0 (control): A's own subscriber gets TSPI, B nothing.
# Needs real root (`ip netns`); exits 77 (skipped) otherwise. The namespaces, the veth pair and its
# private addresses (10.231.7.0/30) exist only inside the namespaces and are deleted on exit.
# usage: test_tspi_veth.sh BIN_DIR
set -euo pipefail
bin="${1:?usage: test_tspi_veth.sh BIN_DIR}"
if [[ $(id -u) != 0 ]] || ! ip netns list >/dev/null 2>&1; then
  echo "SKIP: needs root and ip netns"; exit 77
fi
suffix="$$_${RANDOM}"
nsa="ldvnav_veth_a_$suffix"; nsb="ldvnav_veth_b_$suffix"
work="$(mktemp -d /tmp/ldv_tspi_veth.XXXXXX)"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
  # Anything still running inside the two namespaces was started by this script.
  for ns in "$nsa" "$nsb"; do
    for p in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$p" 2>/dev/null || true; done
  done
  ip netns del "$nsa" 2>/dev/null || true
  ip netns del "$nsb" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

ip netns add "$nsa"
ip netns add "$nsb"
inA() { ip netns exec "$nsa" "$@"; }
inB() { ip netns exec "$nsb" "$@"; }
# The veth pair is created inside A (names are local to the namespaces), its peer moved to B.
inA ip link add veth_a type veth peer name veth_b netns "$nsb"
inA ip link set lo up; inA ip link set lo multicast on
inB ip link set lo up
inA ip addr add 10.231.7.1/30 dev veth_a; inA ip link set veth_a up multicast on
inB ip addr add 10.231.7.2/30 dev veth_b; inB ip link set veth_b up multicast on
# A: the vehicle bus stays on loopback, the TSPI group goes out on the veth (the multicast route
# deploy/systemd/ldvnav-multicast-route.service sets on a vehicle). B: all multicast on its veth.
inA ip route add 224.0.0.0/4 dev lo
inA ip route add 239.255.77.0/24 dev veth_a
inB ip route add 224.0.0.0/4 dev veth_b

bus="udpm://239.255.76.67:7667?ttl=0"
tspi_url="udpm://239.255.77.1:7668?ttl=1"
failures=0

wait_for_file_line() {  # file text: up to 30 s
  for _ in $(seq 300); do grep -q "$2" "$1" 2>/dev/null && return 0; sleep 0.1; done
  echo "FAIL: no '$2' in $1 within 30 s"; failures=$((failures + 1))
}

stop_after() {  # tenths_of_s pid: waits for the probe to exit, else SIGTERM (it prints its counts)
  for _ in $(seq "$1"); do kill -0 "$2" 2>/dev/null || break; sleep 0.1; done
  kill -TERM "$2" 2>/dev/null || true; wait "$2" || true
}

run_case() {  # ttl expected_remote(min|zero)
  local ttl="$1" expect="$2"
  cat > "$work/tspi_pub_$ttl.yaml" <<YAML
bus_url: "$bus"
tspi: {rate_hz: 20, group: 239.255.77.1, port: 7668, ttl: $ttl, channel: TSPI}
YAML
  # `ip netns exec` execs the program: $! is the program itself (a shell function would be a subshell).
  # Each step waits for its condition (a probe listening, tspi_pub's heartbeat), never a fixed sleep, so
  # a loaded machine only makes it slower. The local probe stops at the 100 TSPI it expects.
  ip netns exec "$nsb" "$bin/tspi_probe" count "$tspi_url" 60 TSPI 100 > "$work/remote_$ttl.txt" 2> "$work/remote_$ttl.err" & local remote=$!; pids+=($remote)
  ip netns exec "$nsa" "$bin/tspi_probe" count "$tspi_url" 60 TSPI 100 > "$work/local_$ttl.txt" 2> "$work/local_$ttl.err" & local local_=$!; pids+=($local_)
  wait_for_file_line "$work/remote_$ttl.err" subscribed; wait_for_file_line "$work/local_$ttl.err" subscribed
  ip netns exec "$nsa" "$bin/tspi_pub" --config "$work/tspi_pub_$ttl.yaml" 2> "$work/tspi_pub_$ttl.log" & local pub=$!; pids+=($pub)
  inA "$bin/tspi_probe" wait "$bus" STATUS_TSPI_PUB 30 || { echo "FAIL: no tspi_pub heartbeat (TTL $ttl)"; failures=$((failures + 1)); }
  inA "$bin/tspi_probe" nav "$bus" 100 5
  # The probes stop by themselves at 100 TSPI; one that has fewer is stopped (and its count printed) 10 s
  # after the publisher ended. With TTL 0 the remote must get nothing: 2 s after the local one has all
  # (same packets, microseconds apart) is plenty to see a leak.
  stop_after 100 "$local_"; stop_after "$([[ $expect == min ]] && echo 100 || echo 20)" "$remote"
  kill -TERM "$pub"; wait "$pub" || { echo "tspi_pub (TTL $ttl) did not exit cleanly"; failures=$((failures + 1)); }
  read -r _ remote_n _ remote_gaps _ remote_resets _ remote_bad < "$work/remote_$ttl.txt"
  read -r _ local_n _ local_gaps _ _ _ _ < "$work/local_$ttl.txt"
  echo "TTL $ttl: namespace A (local) received $local_n TSPI, gaps $local_gaps; namespace B (remote, over the veth) received $remote_n, gaps $remote_gaps, resets $remote_resets, malformed $remote_bad"
  if (( local_n < 90 || local_gaps != 0 )); then echo "FAIL: TTL $ttl: the local subscriber should get ~100 TSPI without gaps"; failures=$((failures + 1)); fi
  if [[ $expect == min ]]; then
    if (( remote_n < 90 || remote_n != local_n || remote_gaps != 0 || remote_resets != 0 )); then
      echo "FAIL: TTL $ttl: the remote subscriber should get every TSPI the local one got, in sequence"; failures=$((failures + 1))
    fi
  elif (( remote_n != 0 )); then
    echo "FAIL: TTL $ttl: TSPI left the host"; failures=$((failures + 1))
  fi
}

run_case 1 min
run_case 0 zero
if (( failures > 0 )); then
  echo "test_tspi_veth: $failures failure(s)"; for f in "$work"/*.log; do echo "== $f"; cat "$f"; done; exit 1
fi
echo "test_tspi_veth: passed"
