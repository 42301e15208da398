#!/usr/bin/env bash
# Runs a command inside a fresh private network namespace whose loopback carries multicast, so
# integration tests never send a packet to a real network (DESIGN.md section 1).
set -euo pipefail
exec unshare -rn bash -c 'ip link set lo up && ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo && exec "$@"' netns "$@"
