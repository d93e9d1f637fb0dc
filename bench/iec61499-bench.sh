#!/usr/bin/env bash
# IEC 61499 frontend: translating an application of N chained blocks (each
# an E_CTU counting the events an E_SPLIT passes on, all started by one
# E_CYCLE), and exploring it.
# Usage: bench/iec61499-bench.sh [BUILD_DIR] [BLOCKS...]
set -euo pipefail
build=${1:-build}
shift || true
sizes=${*:-"10 100 1000"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
gen() {
  local n=$1
  {
    echo '<System Name="Bench"><Application Name="Chain"><SubAppNetwork>'
    echo '<FB Name="boot" Type="E_RESTART"/>'
    echo '<FB Name="tick" Type="E_CYCLE"><Parameter Name="DT" Value="T#10ms"/></FB>'
    for i in $(seq 1 "$n"); do
      echo "<FB Name=\"s$i\" Type=\"E_SPLIT\"/>"
      echo "<FB Name=\"c$i\" Type=\"E_CTU\"><Parameter Name=\"PV\" Value=\"2\"/></FB>"
      echo "<FB Name=\"r$i\" Type=\"E_SWITCH\"/>"
    done
    echo '<EventConnections>'
    echo '<Connection Source="boot.COLD" Destination="tick.START"/>'
    echo '<Connection Source="tick.EO" Destination="s1.EI"/>'
    for i in $(seq 1 "$n"); do
      echo "<Connection Source=\"s$i.EO1\" Destination=\"c$i.CU\"/>"
      echo "<Connection Source=\"c$i.CUO\" Destination=\"r$i.EI\"/>"
      echo "<Connection Source=\"r$i.EO1\" Destination=\"c$i.R\"/>"
      [ "$i" -lt "$n" ] && echo "<Connection Source=\"s$i.EO2\" Destination=\"s$((i + 1)).EI\"/>"
    done
    echo '</EventConnections><DataConnections>'
    for i in $(seq 1 "$n"); do
      echo "<Connection Source=\"c$i.Q\" Destination=\"r$i.G\"/>"
    done
    echo '</DataConnections></SubAppNetwork></Application></System>'
  } > "$tmp/chain$n.sys"
}
for n in $sizes; do
  gen "$n"
  echo "== $n blocks of three FBs ($(wc -c < "$tmp/chain$n.sys") bytes)"
  /usr/bin/time -f "   translate: %e s, peak RSS %M KiB" \
    "$build/bin/netlift" translate "$tmp/chain$n.sys" -o "$tmp/chain$n.net"
  echo "   NetIR: $(wc -c < "$tmp/chain$n.net") bytes"
  if [ "$n" -le 100 ]; then
    "$build/bin/netlift" reach "$tmp/chain$n.net" --summary json -q \
      --max-states 2000000 || true
    echo
  fi
done
