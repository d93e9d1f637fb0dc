#!/usr/bin/env bash
# NetIR parse + verify + print throughput and peak memory on generated
# modules. Usage: bench/run.sh [BUILD_DIR] [SIZES_MB...]
set -euo pipefail
build=${1:-build}
shift || true
sizes=${*:-10 100}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for mb in $sizes; do
  "$build/bin/gen-net" "$mb" -o "$tmp/big.net"
  echo "== ${mb} MB"
  "$build/bin/netir-bench" "$tmp/big.net" --repeat 3
  echo "-- netlift translate (whole tool, to /dev/null):"
  /usr/bin/time -f "   %e s, peak RSS %M KiB" \
    "$build/bin/netlift" translate "$tmp/big.net" -o /dev/null
done
