#!/usr/bin/env bash
# What `reduce` removes and what it costs, on the bench models and on
# translated corpus programs closed with nothing (free inputs).
# Usage: bench/reduce-bench.sh [BUILD_DIR]
# Prints, per model: states before/after, state-vector bytes before/after,
# and the time of `opt -p flatten,reduce`.
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
nl="$build/bin/netlift"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
row() {
  local name=$1 file=$2
  "$nl" opt "$file" -p flatten -o "$tmp/flat.net" 2>/dev/null || { echo "$name: not translated"; return; }
  local t0 t1
  t0=$(date +%s.%N)
  "$nl" opt "$tmp/flat.net" -p reduce -o "$tmp/red.net"
  t1=$(date +%s.%N)
  local a b
  a=$("$nl" reach "$tmp/flat.net" --summary json -q --max-states 2000000 || true)
  b=$("$nl" reach "$tmp/red.net" --summary json -q --max-states 2000000 || true)
  python3 - "$name" "$a" "$b" "$t0" "$t1" <<'PY'
import json, sys
name, a, b, t0, t1 = sys.argv[1], json.loads(sys.argv[2]), json.loads(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
print(f"{name:40} states {a['states']:>9} -> {b['states']:<9} vector {a['state_vector_bytes']:>3} -> {b['state_vector_bytes']:<3} B  reduce {t1-t0:6.3f} s")
PY
}
for spec in "philosophers 10" "ring 9" "prodcons 20" "closedloop 4"; do
  python3 "$here/gen-models.py" $spec > "$tmp/m.net"
  row "$spec" "$tmp/m.net"
done
st="$here/../../shared/corpus/st"
if [ -d "$st" ]; then
  find "$st" -name '*.st' | sort | head -40 | while read -r f; do
    "$nl" translate "$f" -o "$tmp/st.net" 2>/dev/null || continue
    row "${f#$st/}" "$tmp/st.net"
  done
fi
