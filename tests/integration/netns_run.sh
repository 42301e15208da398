#!/usr/bin/env bash
# Runs a command inside a fresh private network namespace whose loopback carries multicast, so
# integration tests never send a packet to a real network (DESIGN.md section 1). As real root the
# namespace is a network namespace only (unshare -n), so the command keeps root's CAP_SYS_NICE and can
# use the real-time scheduling the units ship (scripts/bench_bus.sh); otherwise a user namespace maps
# the user to root in it (unshare -rn), where real-time scheduling is refused.
set -euo pipefail
if [[ $(id -u) == 0 ]]; then ns=(unshare -n); else ns=(unshare -rn); fi
exec "${ns[@]}" bash -c 'ip link set lo up && ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo && exec "$@"' netns "$@"
