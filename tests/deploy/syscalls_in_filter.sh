#!/usr/bin/env bash
# Every system call the services make in a short bus benchmark (scripts/bench_bus.sh: fusion, tspi_pub,
# imu_acq, gnss_link, ldv_logger at 600 Hz, started, run, stopped with SIGTERM) is inside the
# SystemCallFilter= of its unit, none maps memory writable and executable (MemoryDenyWriteExecute=), and
# none opens a /proc file that ProcSubset=pid hides.
# systemd is not PID 1 in the test environment, so the filter cannot be tried for real: strace records
# the calls, `systemd-analyze syscall-filter` expands the unit's groups. Exits 77 without strace.
# usage: syscalls_in_filter.sh SOURCE_DIR BIN_DIR [SECONDS]
set -euo pipefail
src="$1"; bin="$2"; seconds="${3:-8}"
command -v strace >/dev/null || { echo "SKIP: strace not installed"; exit 77; }
work="$(mktemp -d /tmp/ldv_syscalls.XXXXXX)"; trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin" "$work/trace"
declare -A unit=([fusion]=ldvnav-fusion [tspi_pub]=ldvnav-tspi-pub [imu_acq]=ldvnav-imu-acq [gnss_link]=ldvnav-gnss-link
                 [ldv_logger]=ldvnav-logger)
for b in "$bin"/*; do ln -s "$b" "$work/bin/$(basename "$b")"; done
# Each service's wrapper has strace attach to it and then execs the service, so the bench's SIGTERM
# reaches the service itself (a service under `exec strace` outlives strace's exit on SIGTERM).
for s in "${!unit[@]}"; do
  rm "$work/bin/$s"
  cat > "$work/bin/$s" <<WRAP
#!/bin/bash
strace -f -qq -o "$work/trace/$s.\$\$" -p \$\$ 2>/dev/null &
for _ in \$(seq 1000); do grep -q '^TracerPid:[[:space:]]*[1-9]' /proc/\$\$/status && break; sleep 0.01; done
exec "$bin/$s" "\$@"
WRAP
  chmod +x "$work/bin/$s"
done
# Exit 3 (messages lost) is no failure here: strace slows the services down; only their calls matter.
rc=0; "$src/tests/integration/netns_run.sh" "$bin/ldv_bus_bench" --bin "$work/bin" --duration "$seconds" --out "$work/bench" > "$work/bench.txt" 2>&1 || rc=$?
if (( rc != 0 && rc != 3 )); then echo "the benchmark failed (exit $rc):"; cat "$work/bench.txt"; exit 1; fi
# The system calls a filter item stands for: a group's members (groups nest), or the call itself.
declare -A group_cache=()
expand() {
  local item="$1" line
  if [[ $item != @* ]]; then echo "$item"; return; fi
  if [[ -z "${group_cache[$item]:-}" ]]; then
    local members=()
    while IFS= read -r line; do
      line="${line// /}"
      [[ -z $line || $line == \#* || $line == "$item" ]] && continue
      if [[ $line == @* ]]; then members+=($(expand "$line")); else members+=("$line"); fi
    done < <(systemd-analyze syscall-filter --no-pager "$item")
    group_cache[$item]="${members[*]}"
  fi
  echo "${group_cache[$item]}"
}
failures=0
# rtkrcv as its unit starts it (ExecStart= as written, the configuration's receiver and corrections
# streams pointed at closed local TCP ports): it must still run after 4 s (not print its usage or fail
# to open a console and exit), with its calls inside its filter too.
if command -v rtkrcv >/dev/null; then
  mkdir -p "$work/rtkrcv"
  sed -e 's#^inpstr1-type *=.*#inpstr1-type =tcpcli#' -e 's#^inpstr1-path *=.*#inpstr1-path =127.0.0.1:52011#' \
      -e 's#^inpstr2-path *=.*#inpstr2-path =user:pw@127.0.0.1:52012/MOUNT#' \
      "$src/deploy/rtklib/rtkrcv_instantaneous_ar.conf" > "$work/rtkrcv/rtkrcv.conf"
  read -r -a exec_start <<< "$(sed -n 's/^ExecStart=//p' "$src/deploy/systemd/ldvnav-rtkrcv.service")"
  exec_start=("${exec_start[@]/\/etc\/ldvnav\/rtkrcv.conf/$work/rtkrcv/rtkrcv.conf}")
  rc=0; (cd "$work/rtkrcv" && "$src/tests/integration/netns_run.sh" timeout -s TERM 4 strace -f -qq -o "$work/trace/rtkrcv.1" \
        "${exec_start[@]}" < /dev/null > "$work/rtkrcv/out.txt" 2>&1) || rc=$?
  if (( rc != 124 )); then  # 124: timeout stopped it, so it was still running
    echo "FAIL: rtkrcv as ldvnav-rtkrcv.service starts it (${exec_start[*]}) exited ($rc) within 4 s:"; tail -5 "$work/rtkrcv/out.txt"
    failures=$((failures + 1))
  else
    echo "rtkrcv: still running 4 s after its unit's ExecStart= (${exec_start[*]})"
  fi
  unit[rtkrcv]=ldvnav-rtkrcv
fi
for s in "${!unit[@]}"; do
  f="$src/deploy/systemd/${unit[$s]}.service"
  traces=("$work"/trace/"$s".*)
  [[ -e "${traces[0]}" ]] || { echo "FAIL: no trace of $s"; failures=$((failures + 1)); continue; }
  # The unit's allow list: every SystemCallFilter= line in order; a line starting with ~ removes.
  declare -A allowed=()
  while IFS= read -r line; do
    deny=0; [[ $line == \~* ]] && { deny=1; line="${line#\~}"; }
    for item in $line; do
      for call in $(expand "$item"); do
        if (( deny )); then unset "allowed[$call]"; else allowed[$call]=1; fi
      done
    done
  done < <(sed -n 's/^SystemCallFilter=//p' "$f")
  (( ${#allowed[@]} > 0 )) || { echo "FAIL: ${unit[$s]}.service has no SystemCallFilter="; failures=$((failures + 1)); continue; }
  # From the service's own execve on (before it, the wrapper's shell waited for strace to attach).
  for t in "${traces[@]}"; do awk -v exe="/$s\", [" '/ execve\(/ && index($0, exe) && !/ENOENT/ { on = 1 } on' "$t" > "$t.service" && mv "$t.service" "$t"; done
  used="$(cat "${traces[@]}" | sed -n 's/^[0-9]* *\([a-z0-9_]*\)(.*/\1/p' | sort -u)"
  outside=()
  # execve is strace starting the service (systemd execs it before the filter applies).
  for call in $used; do [[ $call == execve || -n "${allowed[$call]:-}" ]] || outside+=("$call"); done
  # MemoryDenyWriteExecute=: no mapping both writable and executable, no mprotect adding execute.
  wx="$(cat "${traces[@]}" | grep -E '^[0-9]+ +(mmap|mprotect|pkey_mprotect)\(' | grep PROT_EXEC |
        grep -E 'PROT_WRITE|^[0-9]+ +(mprotect|pkey_mprotect)\(' || true)"
  if (( ${#outside[@]} > 0 )); then
    echo "FAIL: $s calls outside the SystemCallFilter= of ${unit[$s]}.service: ${outside[*]}"; failures=$((failures + 1))
  else
    echo "$s: $(wc -w <<< "$used") distinct system calls, all inside ${unit[$s]}.service's filter"
  fi
  # ProcSubset=pid hides every /proc file but the processes' own: none may be opened (successfully or not).
  if grep -q '^ProcSubset=pid' "$f"; then
    proc="$(cat "${traces[@]}" | grep -oE '^[0-9]+ +(open|openat|stat|newfstatat|access|readlink)[a-z0-9]*\([^"]*"/proc/[^"]*"' |
            grep -oE '"/proc/[^"]*"' | grep -vE '^"/proc/(self|thread-self|[0-9]+)(/|")' | sort -u || true)"
    if [[ -n "$proc" ]]; then echo "FAIL: $s opens /proc files ProcSubset=pid hides: $proc"; failures=$((failures + 1)); fi
  fi
  if [[ -n "$wx" ]]; then echo "FAIL: $s maps memory writable and executable:"; echo "$wx" | head -3; failures=$((failures + 1)); fi
  unset allowed
done
(( failures == 0 )) || exit 1
