#!/usr/bin/env python3
"""Cross-checks input splitting against enumeration (docs/semantics.md,
"Free inputs"): for each model, `netlift reach --format json` runs with
--inputs=split and with --inputs=enumerate, and the two state spaces must be
the same: the same set of states (by their values) and the same successor
relation (as a set of (state, label, state) triples). State numbers may
differ: the two modes meet successors in different orders.

Usage: split-vs-enumerate.py NETLIFT [--max-states N] [--extra ARG]...
         [--split-extra ARG]... (--split-extra: for the split run only)
         [--list FILE] MODEL...
(--list: a file naming one model per line, taken in sorted order.)
Prints one line per model ("same: NAME: S states, E edges"; "skipped" when
both stop at --max-states, "both refuse" when both stop with an error,
"split only" when only enumeration refuses, for too many values) and
a count of each at the end; exits 1 at the first difference, saying what
differs.
"""
import json
import os
import subprocess
import sys


# Refusals of enumeration itself (not of the model): the inputs have too
# many values to try each at every step.
ENUMERATION_LIMITS = ["has no range", "cannot enumerate its values",
                      "valuations per step"]


def space(netlift, model, mode, extra, split_extra):
    cmd = [netlift, "reach", model, "--format", "json", "-o", "-",
           "--inputs=" + mode] + extra + (split_extra if mode == "split" else [])
    out = subprocess.run(cmd, capture_output=True, text=True, errors="replace")
    try:
        data = json.loads(out.stdout)  # also when stopped at --max-states
    except ValueError:
        return None, out.stderr.strip()
    values = {s["id"]: tuple(s["values"]) for s in data["states"]}
    states = set(values.values())
    edges = {(values[e["from"]], e["label"], values[e["to"]])
             for e in data["edges"]}
    return (states, edges, data["complete"]), None


def main():
    args = sys.argv[1:]
    netlift = args.pop(0)
    extra = []
    split_extra = []
    models = []
    while args:
        a = args.pop(0)
        if a == "--extra":
            extra.append(args.pop(0))
        elif a == "--split-extra":
            split_extra.append(args.pop(0))
        elif a == "--list":
            with open(args.pop(0)) as f:
                models += sorted(line.strip() for line in f if line.strip())
        elif a == "--max-states":
            extra += ["--max-states", args.pop(0)]
        else:
            models.append(a)
    counts = {"same": 0, "skipped": 0, "both refuse": 0, "split only": 0}
    for model in models:
        name = os.path.basename(model)
        split, err_split = space(netlift, model, "split", extra, split_extra)
        enum, err_enum = space(netlift, model, "enumerate", extra, split_extra)
        if split is None or enum is None:
            if split is None and enum is None:
                print("both refuse: %s" % name)
                counts["both refuse"] += 1
                continue
            if split is not None and any(
                    why in err_enum for why in ENUMERATION_LIMITS):
                print("split only: %s: %d states, %d edges" %
                      (name, len(split[0]), len(split[1])))
                counts["split only"] += 1
                continue
            print("DIFFERENT: %s: split %s, enumerate %s" %
                  (name, err_split or "explores", err_enum or "explores"))
            return 1
        if not split[2] and not enum[2]:
            print("skipped: %s: more than --max-states" % name)
            counts["skipped"] += 1
            continue
        if split[2] != enum[2]:
            print("DIFFERENT: %s: one exploration incomplete" % name)
            return 1
        for what, s, e in (("states", split[0], enum[0]),
                           ("edges", split[1], enum[1])):
            if s != e:
                print("DIFFERENT: %s: %s only split %s, only enumerate %s" %
                      (name, what, sorted(s - e)[:3], sorted(e - s)[:3]))
                return 1
        print("same: %s: %d states, %d edges" %
              (name, len(split[0]), len(split[1])))
        counts["same"] += 1
    print("checked: %d same, %d split only, %d skipped, %d both refuse" %
          (counts["same"], counts["split only"], counts["skipped"],
           counts["both refuse"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
