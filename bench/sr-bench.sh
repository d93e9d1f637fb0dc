#!/usr/bin/env bash
# Structural reasoning over a large state file: a synthetic file in the
# format of `reach --format json` (compact, one state a line) with N states,
# 20 Boolean attributes (at most 4096 regions) and 2 edges per state to neighbouring states, classified by `netlift sr`
# with all 20 attributes (and once with 5 predicates over them).
# Usage: bench/sr-bench.sh [BUILD_DIR] [STATES]   (default 10000000)
# Prints: file size, seconds, states/s, MB/s, peak RSS.
set -euo pipefail
build=${1:-build}
states=${2:-10000000}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$tmp/s.json" "$states" <<'PY'
import random, sys
path, n = sys.argv[1], int(sys.argv[2])
rng = random.Random(1)
k = 20
with open(path, "w") as f:
    f.write('{"model":"Synthetic","complete":true,"attributes":[')
    f.write(",".join('{"name":"a%d","kind":"place"}' % i for i in range(k)))
    f.write('],\n"states":[\n')
    # Attributes derived from a random walk over 12 hidden bits (12 of
    # them the bits, 8 conjunctions of neighbours): at most 4096 regions,
    # as a model's sensors and actuators are correlated.
    h = 0
    rows = []
    for s in range(n):
        h ^= 1 << rng.randrange(12)
        bits = [h >> i & 1 for i in range(12)]
        bits += [bits[i] & bits[i + 1] for i in range(8)]
        vals = ",".join("1" if b else "0" for b in bits)
        rows.append('{"id":%d,%s"values":[%s]}' % (s, '"deadlock":true,' if s % 100000 == 99999 else "", vals))
        if len(rows) == 100000:
            f.write(",\n".join(rows) + (",\n" if s + 1 < n else "\n"))
            rows = []
    if rows:
        f.write(",\n".join(rows) + "\n")
    f.write('],\n"edges":[\n')
    out = []
    for s in range(n):
        # Edges as in a real state space, where a step changes few
        # attributes: to the next and to the previous state of the walk
        # (one hidden bit apart; the number of region pairs, which the
        # attribute graph keeps, grows with far jumps, not with states).
        for t in ((s + 1) % n, (s - 1) % n):
            out.append('{"from":%d,"to":%d}' % (s, t))
        if len(out) >= 200000:
            f.write(",\n".join(out) + (",\n" if s + 1 < n else "\n"))
            out = []
    if out:
        f.write(",\n".join(out) + "\n")
    f.write("]}\n")
PY
size=$(stat -c %s "$tmp/s.json")
attrs=()
for i in $(seq 0 19); do attrs+=(--attr "a$i"); done
measure() {
  local label=$1; shift
  local start end rss
  start=$(date +%s.%N)
  /usr/bin/time -f "%M" "$build/bin/netlift" sr "$tmp/s.json" "$@" -o "$tmp/report.txt" 2>"$tmp/rss"
  end=$(date +%s.%N)
  rss=$(tail -1 "$tmp/rss")
  python3 -c "
import sys
n, size, t, rss = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]) - float(sys.argv[4]), int(sys.argv[5])
print(f'{sys.argv[6]:28} {n} states, file {size/1e6:.0f} MB: {t:.2f} s, {n/t/1e6:.2f} M states/s, {size/t/1e6:.0f} MB/s, peak RSS {rss/1024:.0f} MB')
" "$states" "$size" "$end" "$start" "$rss" "$label"
}
measure "20 column attributes" "${attrs[@]}"
measure "5 predicates" --attr 'x=a0 and not a1' --attr 'y=a2 or a3' \
  --attr 'z=a4 + a5 + a6 >= 2' --attr 'w=a7 != a8' --attr 'v=a9'
grep -E "^states:|regions" "$tmp/report.txt" | head -2
