#!/usr/bin/env bash
# The unity build (cmake/fast_build.cmake) compiles a target's sources in batches, each batch one translation
# unit. Two files of a batch that both define a file-local name (an anonymous-namespace or static function,
# constant or type) then share it: the same signature fails to compile, another signature silently becomes an
# overload a call may resolve to. This check lists every name defined at file scope (column 0, the style of the
# tree) in more than one file of the same batch, so neither can happen unnoticed.
# usage: check_unity_batches.sh BUILD_DIR   (exit 0: no shared names, 77: the build is not a unity build)
set -euo pipefail
build=${1:?usage: check_unity_batches.sh BUILD_DIR}
mapfile -t batches < <(find "$build" -path '*/Unity/unity_*' -name '*.cxx' | sort)
if ((${#batches[@]} == 0)); then
  echo "no unity batches under $build (configured with LDV_UNITY_BUILD=OFF): nothing to check"
  exit 77
fi

# Names a file defines at file scope: functions (not Class::member), constants and variables, types.
file_scope_names() {
  awk '
    /^(namespace|template|#|\/\/|}|TEST|return|using namespace)/ { next }
    /^(struct|class|enum class|enum|union) [A-Za-z_][A-Za-z0-9_]*[ {:]/ {
      sub(/^(struct|class|enum class|enum|union) /, ""); sub(/[ {:].*/, ""); print; next }
    /^using [A-Za-z_][A-Za-z0-9_]* =/ { sub(/^using /, ""); sub(/ =.*/, ""); print; next }
    /^[A-Za-z_][^;(=]*[ *&][A-Za-z_][A-Za-z0-9_]*\(/ && !/;[ ]*$/ {
      line = $0; sub(/\(.*/, "", line)
      if (line ~ /::[A-Za-z_][A-Za-z0-9_]*$/ || line ~ /operator/) next
      n = split(line, w, /[ *&]+/); print w[n]; next }
    /^(static |inline )*(constexpr|const) [^(;]*[ *&][A-Za-z_][A-Za-z0-9_]*( =| \{|\[|\{)/ {
      line = $0; sub(/( =| \{|\[|\{).*/, "", line); n = split(line, w, /[ *&]+/); print w[n]; next }
  ' "$1" | sort -u
}

shared=0
for batch in "${batches[@]}"; do
  mapfile -t files < <(sed -n 's/^#include "\(.*\)"$/\1/p' "$batch")
  ((${#files[@]} > 1)) || continue
  dup=$(for f in "${files[@]}"; do file_scope_names "$f" | sed "s|\$| $f|"; done |
        awk '{ n[$1]++; where[$1] = where[$1] "\n      " $2 } END { for (k in n) if (n[k] > 1) print "  " k ":" where[k] }')
  if [[ -n $dup ]]; then
    echo "${batch#"$build"/}: names defined in more than one file of the batch"
    echo "$dup"
    shared=1
  fi
done
if ((shared)); then
  echo "rename them, share one definition through a header, or keep the file out of the batch (SKIP_UNITY_BUILD_INCLUSION)"
  exit 1
fi
echo "${#batches[@]} unity batches: no file-scope name defined twice in a batch"
