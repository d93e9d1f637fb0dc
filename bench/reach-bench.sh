#!/usr/bin/env bash
# State-space exploration throughput on scalable models and the MCC corpus.
# Usage: bench/reach-bench.sh [BUILD_DIR]
# Prints, per model: states, edges, states/s, bytes/state, peak RSS.
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() {
  local name=$1 file=$2
  local out
  out=$(/usr/bin/time -f "%M" "$build/bin/netlift" reach "$file" --summary json -q 2>"$tmp/rss")
  python3 - "$name" "$out" "$(tail -1 "$tmp/rss")" <<'PY'
import json, sys
name, s, rss = sys.argv[1], json.loads(sys.argv[2]), int(sys.argv[3])
print(f"{name:34} {s['states']:>10} states {s['transitions']:>11} edges "
      f"{s['states_per_second']:>10.0f} states/s {s['bytes_per_state']:>7.2f} B/state "
      f"(vector {s['state_vector_bytes']} B) peak RSS {rss/1024:.0f} MB")
PY
}
for spec in "philosophers 10" "philosophers 16" "ring 9" "prodcons 20" "closedloop 4" "closedloop 6"; do
  python3 "$here/gen-models.py" $spec > "$tmp/m.net"
  run "$spec" "$tmp/m.net"
done
corpus="$here/../../shared/corpus/pnml/mcc2021"
if [ -d "$corpus" ]; then
  for m in AirplaneLD-PT-0010 Referendum-PT-0010 RefineWMG-PT-002002 HexagonalGrid-PT-110 Peterson-PT-2; do
    run "$m" "$corpus/PT/$m/model.pnml"
  done
else
  echo "(MCC corpus not found beside the checkout: skipped)"
fi
# Side by side with spin on the same models (netlift's Promela export; pan
# breadth-first without reduction; spin's figure is its whole run).
if command -v spin >/dev/null && command -v cc >/dev/null; then
  echo "-- netlift vs spin 6.5.2 (same state graphs checked) --"
  models=()
  for spec in "philosophers 10" "philosophers 16" "ring 7" "prodcons 10" "closedloop 3" "closedloop 4"; do
    f="$tmp/${spec// /}.net"
    python3 "$here/gen-models.py" $spec > "$f"
    models+=("$f")
  done
  if [ -d "$corpus" ]; then
    for m in AirplaneLD-PT-0010 Referendum-PT-0010 RefineWMG-PT-002002 HexagonalGrid-PT-110 Peterson-PT-2; do
      models+=("$corpus/PT/$m/model.pnml")
    done
  fi
  python3 "$here/../scripts/check-spin.py" --bench "$build/bin/netlift" "${models[@]}"
else
  echo "(spin not installed: the side-by-side comparison is skipped)"
fi
