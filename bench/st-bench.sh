#!/usr/bin/env bash
# Structured Text frontend throughput: the whole ST corpus (every file,
# translated or refused) and a large generated program.
# Usage: bench/st-bench.sh [BUILD_DIR] [STATIONS]
set -euo pipefail
build=${1:-build}
stations=${2:-2000}
here=$(cd "$(dirname "$0")" && pwd)
corpus="$here/../../shared/corpus/st"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ -d "$corpus" ]; then
  echo "== ST corpus"
  find "$corpus" -type f \( -name '*.st' -o -name '*.txt' -o -name '*.test' \) \
    ! -name PROVENANCE.txt -print0 | sort -z |
    xargs -0 "$build/bin/st-bench" --repeat 3
fi
python3 "$here/gen-st.py" "$stations" > "$tmp/big.st"
echo "== generated program, $stations stations"
"$build/bin/st-bench" --repeat 3 "$tmp/big.st"
echo "-- netlift translate (whole tool, to /dev/null):"
/usr/bin/time -f "   %e s, peak RSS %M KiB" \
  "$build/bin/netlift" translate "$tmp/big.st" -o /dev/null
