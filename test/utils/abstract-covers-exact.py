#!/usr/bin/env python3
"""Soundness oracle of --timers=abstract: every state of the exact model,
without its abstracted clocks' values, is a state of the abstract model
(without the values the abstraction adds). Prints one line per model and a count; exits 1 on a violation.

usage: abstract-covers-exact.py NETLIFT [--max-states N] [--list FILE] MODEL...
A model that either mode refuses, or that a limit stops, is skipped.
"""
import csv
import io
import json
import subprocess
import sys


def run(netlift, args):
    return subprocess.run([netlift, *args], capture_output=True, text=True,
                          timeout=300)


def states(netlift, model, mode, limit):
    r = run(netlift, ["reach", model, "--timers=" + mode, "--inputs=split",
                      "--format", "csv",
                      "--max-states", str(limit), "-q"])
    if r.returncode != 0:
        return None
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    return rows


def main():
    args = sys.argv[1:]
    netlift = args.pop(0)
    limit = 200000
    models = []
    while args:
        a = args.pop(0)
        if a == "--max-states":
            limit = int(args.pop(0))
        elif a == "--list":
            models += [l.strip() for l in open(args.pop(0)) if l.strip()]
        else:
            models.append(a)
    counts = {"covered": 0, "no timers": 0, "skipped": 0, "VIOLATED": 0}
    for model in models:
        exact = states(netlift, model, "exact", limit)
        abstract = states(netlift, model, "abstract", limit)
        if exact is None or abstract is None:
            counts["skipped"] += 1
            continue
        flags = [c for c in (abstract[0].keys() if abstract else [])
                 if c.endswith(".ticked")]
        clocks = {f[:-len(".ticked")] for f in flags}
        if not clocks:
            counts["no timers"] += 1
            continue
        drop = clocks | set(flags) | {"id", "deadlock"}
        cols = [c for c in exact[0].keys() if c not in drop]
        seen = {tuple(row[c] for c in cols) for row in abstract}
        missing = [row for row in exact
                   if tuple(row[c] for c in cols) not in seen]
        name = model.rsplit("/", 1)[-1]
        if missing:
            counts["VIOLATED"] += 1
            print(f"VIOLATED {name}: {len(missing)} exact states not in the "
                  f"abstract model, e.g. {dict((c, missing[0][c]) for c in cols)}")
        else:
            counts["covered"] += 1
            print(f"covered {name}: {len(clocks)} timers, exact "
                  f"{len(exact)} states, abstract {len(abstract)}")
    print("checked: " + ", ".join(f"{v} {k}" for k, v in counts.items()))
    return 1 if counts["VIOLATED"] else 0


if __name__ == "__main__":
    sys.exit(main())
