#!/usr/bin/env bash
# The dependency direction of the source tree: libraries never include the services, and the
# services include each other only through common/ (a service may die or be replaced alone).
#   estimator/, toolbox/, common/, input/   must not include services/
#   input/                          must not include estimator/, toolbox/ nor tools/ (common/ not input/)
#   services/imu_acq/               must not include services/gnss_link/ nor toolbox/
# Prints every offending file:line and exits 1; tools/ may include services/ (ldv nav replays logs
# through the fusion engine).
set -euo pipefail
src_dir="$1"
cd "$src_dir"
include='^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]'
bad=0
check() {  # folders..., then the forbidden include prefix as the last argument
  local prefix="${*: -1}" dirs=("${@:1:$#-1}") hits
  hits="$(grep -rnE --include='*.hpp' --include='*.cpp' --include='*.h' --include='*.cc' \
            "${include}${prefix}" "${dirs[@]}" || true)"
  if [[ -n "$hits" ]]; then
    printf '%s must not include %s:\n%s\n' "${dirs[*]}" "$prefix" "$hits"
    bad=1
  fi
}
check estimator toolbox common input 'services/'
# The input layer sits below the estimator and the toolbox: it reads files into records and knows no filter.
check input 'estimator/'
check input 'toolbox/'
check input 'tools/'
check common 'input/'
check services/imu_acq 'services/gnss_link/'
check services/imu_acq 'toolbox/'
if (( bad )); then exit 1; fi
echo "include direction respected"
