#!/usr/bin/env bash
# Enforcement throughput: a long conform trace of the Guignard-Faure example
# (with desynchronised readings to suppress) through `netlift enforce`.
# Usage: bench/enforce-bench.sh [BUILD_DIR] [MILLION_VECTORS]
set -euo pipefail
build=${1:-build}
millions=${2:-5}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/spec.kiss2" <<'K'
.i 2
.o 2
.r s1
00 s1 s1 00
10 s1 s1 00
01 s1 s3 10
11 s1 s2 11
11 s2 s2 11
10 s2 s2 11
01 s2 s2 11
00 s2 s1 00
01 s3 s3 10
11 s3 s3 10
00 s3 s1 00
10 s3 s1 00
.e
K
python3 - "$tmp/trace.csv" "$millions" <<'PY'
import sys
path, m = sys.argv[1], int(float(sys.argv[2]) * 1_000_000)
cycle = ["0,0,0,0", "1,1,0,0", "1,1,1,1", "1,0,1,1"]
with open(path, "w") as f:
    f.write("i1,i2,o1,o2\n")
    block = "\n".join(cycle) + "\n"
    f.write(block * (m // 4))
PY
size=$(stat -c %s "$tmp/trace.csv")
start=$(date +%s.%N)
/usr/bin/time -f "%M" -o "$tmp/rss" "$build/bin/netlift" enforce "$tmp/spec.kiss2" "$tmp/trace.csv" > "$tmp/out"
end=$(date +%s.%N)
tail -1 "$tmp/out"
python3 - "$start" "$end" "$millions" "$size" "$(cat "$tmp/rss")" <<'PY'
import sys
s, e, m, size, rss = float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
print(f"{m:.1f} M vectors in {e-s:.2f} s: {m/(e-s):.2f} M vectors/s, trace {size/1e6:.0f} MB, peak RSS {rss/1024:.0f} MB")
PY
