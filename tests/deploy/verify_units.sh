#!/usr/bin/env bash
# Checks every systemd unit in deploy/systemd with `systemd-analyze verify` (syntax, directives,
# dependencies, executables), with /opt/ldvnav/bin pointing at this build's binaries.
set -euo pipefail
src_dir="$1"; bin_dir="$2"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
for unit in "$src_dir"/deploy/systemd/*; do
  sed "s#/opt/ldvnav/bin#$bin_dir#g" "$unit" > "$work/$(basename "$unit")"
done
cd "$work"
out="$(SYSTEMD_LOG_LEVEL=notice systemd-analyze verify --man=no ./*.service ./*.target 2>&1 || true)"
# Units we do not ship (e.g. network-online.target of the host) are not our findings.
findings="$(printf '%s\n' "$out" | grep -v -e '^$' -e 'network-online.target' || true)"
if [[ -n "$findings" ]]; then
  printf 'systemd-analyze verify reported:\n%s\n' "$findings"
  exit 1
fi
echo "all $(ls | wc -l) units verified"
