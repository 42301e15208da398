#!/usr/bin/env bash
# `cmake --install` into a scratch root (DESTDIR) lays out every file the installed units and configs name (issue 53):
# each unit's ExecStart program and its --config, its Documentation= files, the /etc/ldvnav files the configs name;
# the units' paths follow the prefix (/opt/ldvnav and /usr/local); a second install keeps a changed config and writes
# the new default beside it as .dist.
# install_layout.sh BUILD_DIR
set -euo pipefail
build="$1"
root="$(mktemp -d)"
trap 'rm -rf "$root"' EXIT
fail=0
say() { echo "install_layout: $*"; }
check_layout() {  # DESTDIR PREFIX
  local dest="$1" prefix="$2" unit file
  for unit in "$dest"/lib/systemd/system/*.service; do
    # the program each ExecStart runs and every absolute path on the line that belongs to the installation
    while read -r file; do
      case "$file" in
        "$prefix"/*|/etc/ldvnav/*) [[ -e "$dest$file" ]] || { say "$(basename "$unit") names $file: not installed"; fail=1; } ;;
      esac
    done < <(grep -E '^(ExecStart|Documentation)=' "$unit" | sed -E 's/^[A-Za-z]+=//; s#file://##' | tr ' ' '\n' | grep '^/')
    grep -q "/opt/ldvnav" "$unit" && [[ "$prefix" != /opt/ldvnav ]] && { say "$(basename "$unit") still names /opt/ldvnav"; fail=1; }
  done
  for file in $(grep -ohE '/etc/ldvnav/[A-Za-z0-9_.-]+' "$dest"/etc/ldvnav/*.yaml | sort -u); do
    [[ -e "$dest$file" ]] || { say "a config names $file: not installed"; fail=1; }
  done
  [[ -x "$dest$prefix/bin/ldv" && -x "$dest$prefix/bin/fusion" ]] || { say "no binaries under $prefix/bin"; fail=1; }
}
DESTDIR="$root/a" cmake --install "$build" --prefix /opt/ldvnav > "$root/a.log"
check_layout "$root/a" /opt/ldvnav
grep -q "^ExecStart=/opt/ldvnav/bin/fusion --config /etc/ldvnav/fusion.yaml" "$root/a/lib/systemd/system/ldvnav-fusion.service" \
  || { say "the fusion unit does not run the installed fusion"; fail=1; }
DESTDIR="$root/b" cmake --install "$build" --prefix /usr/local > "$root/b.log"
check_layout "$root/b" /usr/local
grep -q "^ExecStart=/usr/local/bin/fusion " "$root/b/lib/systemd/system/ldvnav-fusion.service" \
  || { say "with --prefix /usr/local the fusion unit does not follow"; fail=1; }
# A changed config survives a second install; the new default lands beside it.
echo "# changed on the vehicle" >> "$root/a/etc/ldvnav/fusion.yaml"
DESTDIR="$root/a" cmake --install "$build" --prefix /opt/ldvnav > "$root/a2.log"
tail -1 "$root/a/etc/ldvnav/fusion.yaml" | grep -q "changed on the vehicle" || { say "a changed fusion.yaml was overwritten"; fail=1; }
[[ -f "$root/a/etc/ldvnav/fusion.yaml.dist" ]] || { say "no fusion.yaml.dist beside the kept one"; fail=1; }
[[ ! -e "$root/a/etc/ldvnav/tspi_pub.yaml.dist" ]] || { say "an unchanged config got a .dist"; fail=1; }
(( fail == 0 )) && say "every file the units and configs name is installed, under both prefixes; a changed config kept"
exit "$fail"
