#!/usr/bin/env python3
"""The changes of some values along the edges of a state space written by
`netlift reach --format json`: one line `  (values before) -> (values
after)` per distinct change, stuttering left out, sorted as
`smv-explore.py --project` prints them, so that the behaviour of a
netlift model and of an SMV model (fb2smv's reference output) can be
compared on the values they share.

usage: project-states.py STATES.json NAME...
"""
import json
import sys


def main():
    if len(sys.argv) < 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 1
    graph = json.load(open(sys.argv[1]))
    names = [a["name"] for a in graph["attributes"]]
    try:
        cols = [names.index(n) for n in sys.argv[2:]]
    except ValueError as e:
        print(f"project-states: {e}", file=sys.stderr)
        return 1
    values = {s["id"]: tuple(s["values"][c] for c in cols)
              for s in graph["states"]}
    changes = {(values[e["from"]], values[e["to"]]) for e in graph["edges"]
               if values[e["from"]] != values[e["to"]]}
    print("changes:")
    for a, b in sorted(changes, key=repr):
        print(f"  {a} -> {b}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
