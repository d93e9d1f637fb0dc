#!/usr/bin/env bash
# The lifter pipeline end to end: PLC program (Ladder Diagram in PLCopen
# XML) -> closed loop with the plant library -> reduced -> explored ->
# structural-reasoning report, for the faulty controller and the fixed one.
# Usage: examples/lifter/run.sh [NETLIFT] [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
netlift=${1:-$here/../../build/bin/netlift}
out=${2:-$here/../../build/lifter}
# The plant library: lib/plant in the source tree, share/netlift/plant
# where netlift is installed (this script in share/doc/netlift/examples).
lib=$here/../../lib/plant
[ -d "$lib" ] || lib=$here/../../../../netlift/plant
mkdir -p "$out"
attrs=(--attr B1=lt.occupied --attr B2=sl.occupied --attr B3=ut.occupied
       --attr S7=lift.retracted --attr S8=lift.extended --attr M1=lifter.M1
       --attr M2=lifter.M2 --attr M3=lifter.M3 --attr UP=lifter.UP)
for ctl in lifter-faulty lifter; do
  "$netlift" compose "$here/$ctl.xml" "$lib/conveyor.net" "$lib/cylinder.net" \
    "$lib/sensor.net" "$here/lifter-plant.net" --inst lifter:Lifter \
    --inst lt:Conveyor --inst b5:Sensor \
    --inst sl:Conveyor --inst ut:Conveyor --inst lift:Cylinder \
    --inst levels:Levels --inst src:PalletSource --inst line:Mainline \
    --inst panel:Panel \
    --connect "$here/wiring.txt" -q -o "$out/$ctl.net"
  "$netlift" opt "$out/$ctl.net" -p 'flatten,reduce' -o "$out/$ctl-reduced.net"
  "$netlift" sr "$out/$ctl-reduced.net" "${attrs[@]}" --report html \
    --witnesses "$out/$ctl-witnesses" -o "$out/$ctl-report.html"
  "$netlift" sr "$out/$ctl-reduced.net" "${attrs[@]}" --report json \
    -o "$out/$ctl-report.json"
done
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
for ctl, what in (("lifter-faulty", "faulty controller"),
                  ("lifter", "fixed controller")):
    r = json.load(open(f"{out}/{ctl}-report.json"))
    dead = sum(x["deadlocks"] for x in r["regions"])
    keys = r["key_attributes"]["sets"]
    trapped = ", ".join(f'{x["region"]} ({x["states"]} states)'
                        for x in r["regions_never_left"]) or "none"
    print(f"{what}: report {out}/{ctl}-report.html")
    print(f"  states: {r['states']} ({r['edges']} edges), deadlocks: {dead}")
    kind = "exact cover" if r["key_attributes"]["exact"] else \
        f'no exact cover; {r["key_attributes"]["covered_once"]} states have exactly one'
    print(f"  key attributes: " +
          (" or ".join("{" + ",".join(k) + "}" for k in keys) or "none") +
          f" ({kind})")
    print(f"  regions never left: {trapped}")
PY
