#!/usr/bin/env bash
# Timers exact vs abstract (issue 36, docs/reach.md "Timers abstracted"):
#  1. N TOF timers of 4 s at a 20 ms scan, N = 1..4: states and seconds of
#     `reach` exact (stopped at --max-states) and abstract;
#  2. the corpus programs that translate (ST, PLCopen XML, IL): how many
#     reach a complete state space within 10^7 states and LIMIT seconds,
#     exact, abstract, and either.
# Usage: bench/timers-bench.sh [BUILD_DIR] [LIMIT_SECONDS]
set -euo pipefail
build=${1:-build}
limit=${2:-60}
here=$(cd "$(dirname "$0")" && pwd)
corpus="$here/../../shared/corpus"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
netlift="$build/bin/netlift"

summary() { # MODEL MODE MAXSTATES -> "states seconds complete"
  "$netlift" reach "$1" --timers="$2" --inputs=split --max-states "$3" \
    --time-limit "$limit" --summary json -q 2>/dev/null </dev/null |
    tail -1 |
    python3 -c 'import json,sys
try:
  d=json.load(sys.stdin); print(d["states"], "%.2f" % d["seconds"], d["complete"])
except Exception: print("- - refused")' || true
}

echo "== N TOF timers of 4 s at 20 ms (exact stopped at 3000000 states)"
for n in 1 2 3 4; do
  {
    echo "PROGRAM Lights"
    echo "  VAR_INPUT"; for i in $(seq $n); do echo "    b$i : BOOL;"; done; echo "  END_VAR"
    echo "  VAR_OUTPUT all : BOOL; END_VAR"
    echo "  VAR"; for i in $(seq $n); do echo "    t$i : TOF;"; done; echo "  END_VAR"
    for i in $(seq $n); do echo "  t$i(IN := b$i, PT := T#4s);"; done
    echo -n "  all := TRUE"; for i in $(seq $n); do echo -n " AND t$i.Q"; done; echo ";"
    echo "END_PROGRAM"
    echo "CONFIGURATION C RESOURCE R ON PLC"
    echo "  TASK cyc(INTERVAL := T#20ms, PRIORITY := 1);"
    echo "  PROGRAM main WITH cyc : Lights;"
    echo "END_RESOURCE END_CONFIGURATION"
  } > "$tmp/tof$n.st"
  echo "N=$n exact: $(summary "$tmp/tof$n.st" exact 3000000)   abstract: $(summary "$tmp/tof$n.st" abstract 3000000)"
done

if [ -d "$corpus" ]; then
  echo "== corpus programs that translate: complete within 10^7 states and ${limit} s"
  find "$corpus/st" "$corpus/plcopen_xml" "$corpus/il" -type f \
    \( -name '*.st' -o -name '*.xml' -o -name '*.il' \) -print0 | sort -z |
    while IFS= read -r -d '' f; do
      "$netlift" translate "$f" -o /dev/null 2>/dev/null </dev/null || continue
      e=$(summary "$f" exact 10000000)
      a=$(summary "$f" abstract 10000000)
      echo "$e | $a | ${f#$corpus/}"
    done > "$tmp/sweep.txt"
  python3 - "$tmp/sweep.txt" <<'PY'
import sys
rows = [l.rstrip("\n").split(" | ") for l in open(sys.argv[1])]
done = lambda s: s.endswith("True")
explorable = [r for r in rows if not (r[0].endswith("refused") and r[1].endswith("refused"))]
ex = sum(done(r[0]) for r in explorable)
ab = sum(done(r[1]) for r in explorable)
either = sum(done(r[0]) or done(r[1]) for r in explorable)
print(f"translated: {len(rows)}, explorable: {len(explorable)}, complete exact: {ex}, "
      f"abstract: {ab}, either: {either}")
for r in explorable:
    if not done(r[0]) or not done(r[1]):
        print(f"  exact {r[0]:<28} abstract {r[1]:<28} {r[2]}")
PY
fi
