#!/usr/bin/env bash
# The Debian package (issue 53): `cpack -G DEB` from the build; its control declares the shared libraries the
# binaries link (dpkg-shlibdeps) and every /etc/ldvnav file as a conffile; installed with dpkg into a scratch root
# (its own admin folder: the machine's packages are not touched), it lays out the binaries, units and configs, and a
# second `dpkg -i` keeps a changed /etc/ldvnav/fusion.yaml (dpkg's conffile handling, --force-confold as a
# non-interactive integrator answers).
# debian_package.sh BUILD_DIR
set -euo pipefail
build="$(cd "$1" && pwd)"
command -v dpkg-deb > /dev/null && command -v dpkg-shlibdeps > /dev/null || { echo "dpkg-dev missing"; exit 77; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail=0
say() { echo "debian_package: $*"; }
(cd "$tmp" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp/out" > "$tmp/cpack.log" 2>&1) \
  || { cat "$tmp/cpack.log"; exit 1; }
deb="$(ls "$tmp"/out/*.deb)"
info="$(dpkg-deb -I "$deb")"
for lib in liblcm1 libyaml-cpp libspdlog libstdc++6; do
  grep -q "Depends:.*$lib" <<< "$info" || { say "Depends lacks $lib: $(grep Depends <<< "$info")"; fail=1; }
done
conffiles="$(cd "$tmp" && dpkg-deb -e "$deb" control && cat control/conffiles)"
for f in /etc/ldvnav/fusion.yaml /etc/ldvnav/kfgins.yaml /etc/ldvnav/tspi_pub.yaml /etc/ldvnav/rtkrcv.conf; do
  grep -qx "$f" <<< "$conffiles" || { say "$f is not a conffile"; fail=1; }
done
# dpkg into a scratch root with its own database
root="$tmp/root"
mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates"
touch "$root/var/lib/dpkg/status" "$root/var/lib/dpkg/available"
install_deb() {
  dpkg --root="$root" --force-depends --force-script-chrootless --force-confold --log=/dev/null -i "$deb" \
    > "$tmp/dpkg.log" 2>&1 || { cat "$tmp/dpkg.log"; say "dpkg -i failed"; exit 1; }
}
install_deb
for f in opt/ldvnav/bin/fusion opt/ldvnav/bin/tspi_pub opt/ldvnav/bin/ldv lib/systemd/system/ldvnav.target \
         lib/systemd/system/ldvnav-fusion.service etc/ldvnav/fusion.yaml etc/ldvnav/kfgins.yaml etc/sysctl.d/90-ldvnav.conf; do
  [[ -e "$root/$f" ]] || { say "/$f not installed"; fail=1; }
done
grep -q "^ExecStart=/opt/ldvnav/bin/fusion --config /etc/ldvnav/fusion.yaml" "$root/lib/systemd/system/ldvnav-fusion.service" \
  || { say "the fusion unit does not run /opt/ldvnav/bin/fusion"; fail=1; }
"$root/opt/ldvnav/bin/ldv" --help > /dev/null || { say "the installed ldv does not run"; fail=1; }
echo "# changed on the vehicle" >> "$root/etc/ldvnav/fusion.yaml"
install_deb
tail -1 "$root/etc/ldvnav/fusion.yaml" | grep -q "changed on the vehicle" || { say "a second dpkg -i replaced the changed fusion.yaml"; fail=1; }
(( fail == 0 )) && say "$(basename "$deb"): shlibdeps, conffiles, the layout from dpkg, a changed config kept"
exit "$fail"
