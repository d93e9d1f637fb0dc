#!/usr/bin/env bash
# Free inputs split on demand against enumerated (docs/semantics.md, "Free
# inputs"): the interlock family of bench/gen-interlock.py with N Boolean
# inputs. Prints, per N and mode: states, edges, states/s and the step's
# executions per expanded state (classes of input valuations, or
# valuations). Enumeration runs for N = 8 only.
# Usage: bench/inputs-bench.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() {
  local n=$1 mode=$2
  local out
  out=$("$build/bin/netlift" reach "$tmp/i$n.st" --inputs="$mode" \
        --max-input-values 70000 --summary json 2>/dev/null)
  python3 - "$n" "$mode" "$out" <<'PY'
import json, sys
n, mode, s = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
c = s["input_classes"]
print(f"N={n:>3} {mode:10} {s['states']:>6} states {s['transitions']:>7} edges "
      f"{s['states_per_second']:>10.0f} states/s  executions/state "
      f"mean {c['mean']:>8.2f} max {c['max']:>6}  ({s['seconds']:.4f} s)")
PY
}
for n in 8 16 32 64; do
  python3 "$here/gen-interlock.py" "$n" > "$tmp/i$n.st"
  run "$n" split
  # Enumerating N = 16 takes about 100 s (65 536 valuations per state).
  if [ "$n" -le 8 ]; then run "$n" enumerate; fi
done
