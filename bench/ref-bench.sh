#!/usr/bin/env bash
# References: translation time as the number of places grows (every
# dereference selects over every family of its type), and exploration of
# a small instance against the same program without references (the
# state spaces must agree; the time ratio is the cost of the selections).
# Usage: bench/ref-bench.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for n in 50 100 200 400; do
  python3 "$here/gen-refs.py" "$n" > "$tmp/refs$n.st"
  echo "== translate, $n stations through references"
  /usr/bin/time -f "   %e s, peak RSS %M KiB" \
    "$build/bin/netlift" translate "$tmp/refs$n.st" -o /dev/null
done
python3 "$here/gen-refs.py" 7 > "$tmp/small.st"
python3 "$here/gen-refs.py" 7 --index > "$tmp/small-index.st"
echo "== reach, 7 stations: references, then indices"
for f in small small-index; do
  /usr/bin/time -f "   %e s, peak RSS %M KiB" \
    "$build/bin/netlift" reach --ranges <(echo "sel 0..6") "$tmp/$f.st" | head -2
done
