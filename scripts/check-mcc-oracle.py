#!/usr/bin/env python3
"""Cross-checks `netlift reach` against the Model Checking Contest oracle:
for every model listed in oracle-statespace.tsv, the number of reachable
markings, of graph edges, the largest marking of one place and the largest
total marking must match exactly.

usage: check-mcc-oracle.py NETLIFT MCC_DIR
(MCC_DIR holds oracle-statespace.tsv and PT/<model>/model.pnml)
Prints one line per model and a closing 'N passed, M failed' line.
"""
import json
import os
import subprocess
import sys


def main():
    netlift, root = sys.argv[1], sys.argv[2]
    rows = [l.rstrip("\n").split("\t")
            for l in open(os.path.join(root, "oracle-statespace.tsv"))][1:]
    passed = failed = 0
    for model, states, edges, maxp, maxm in rows:
        path = os.path.join(root, "PT", model, "model.pnml")
        r = subprocess.run([netlift, "reach", path, "--summary", "json", "-q"],
                           capture_output=True, text=True, timeout=600)
        if r.returncode != 0:
            print(f"FAIL {model}: exit {r.returncode}: {r.stderr.strip()[:300]}")
            failed += 1
            continue
        got = json.loads(r.stdout)
        want = {"states": int(states), "transitions": int(edges),
                "max_tokens_in_place": int(maxp),
                "max_tokens_per_marking": int(maxm)}
        diff = {k: (got[k], v) for k, v in want.items() if got[k] != v}
        if diff or not got["complete"]:
            print(f"FAIL {model}: (got, expected) {diff}")
            failed += 1
        else:
            print(f"ok   {model}: {states} states, {edges} edges, "
                  f"{got['states_per_second']:.0f} states/s")
            passed += 1
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
