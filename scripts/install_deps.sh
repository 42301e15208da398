#!/usr/bin/env bash
# Installs the Debian 12 packages ldvnav needs to build, test and run (idempotent, non-interactive).
set -euo pipefail
PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config git
  liblcm-dev liblcm-bin libglib2.0-dev
  libeigen3-dev libgeographiclib-dev libspdlog-dev libyaml-cpp-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev libsystemd-dev
  gnuplot-nox rtklib iproute2 pps-tools systemd chromium strace tzdata
  gpsbabel  # reads back what `ldv convert` writes (tests/toolbox_convert)
  gpsd gpsd-clients  # decodes tspi_pub's NMEA output (tests/integration/test_tspi_pub.cpp)
  clang libclang-rt-14-dev  # the libFuzzer run of scripts/test.sh (tests/fuzz/run_libfuzzer.sh)
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
