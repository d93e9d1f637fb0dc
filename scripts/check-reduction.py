#!/usr/bin/env python3
"""Checks a reduction by exploration: the state space of MODEL (flattened)
and of MODEL after PIPELINE, projected on the observed columns, must have
the same set of valuations, and the same deadlock verdict unless
--ignore-deadlocks (reduce-coi does not preserve deadlocks of the removed
part).

  check-reduction.py NETLIFT MODEL PIPELINE [--observe a,b,...] [--ignore-deadlocks]

Observed columns default to every column the reduced state space still has
except clocks (clock readings are what reduce-clocks merges). Prints one
line: the state counts before and after, the number of observed
valuations, and OK or what differs; exits 1 when they differ."""
import csv, io, subprocess, sys


def explore(netlift, model, pipeline=None):
    cmd = [netlift, "opt", model, "-p", "flatten" + ("," + pipeline if pipeline else "")]
    net = subprocess.run(cmd, capture_output=True, text=True)
    if net.returncode:
        sys.exit(f"check-reduction: {' '.join(cmd)} failed:\n{net.stderr}")
    out = subprocess.run([netlift, "reach", "-", "--format", "csv", "-q"],
                         input=net.stdout, capture_output=True, text=True)
    if out.returncode not in (0,):
        sys.exit(f"check-reduction: reach failed:\n{out.stderr}")
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    return rows


def main():
    args = sys.argv[1:]
    ignore = "--ignore-deadlocks" in args
    args = [a for a in args if a != "--ignore-deadlocks"]
    observe = None
    if "--observe" in args:
        i = args.index("--observe")
        observe = args[i + 1].split(",")
        del args[i:i + 2]
    netlift, model, pipeline = args
    before = explore(netlift, model)
    after = explore(netlift, model, pipeline)
    cols = observe or [c for c in (after[0].keys() if after else [])
                       if c not in ("id", "deadlock") and not c.startswith("clock(")]
    for c in cols:
        if before and c not in before[0]:
            sys.exit(f"check-reduction: '{c}' is not a column of the original state space")
        if after and c not in after[0]:
            sys.exit(f"check-reduction: '{c}' is not a column of the reduced state space")
    proj = lambda rows: {tuple(r[c] for c in cols) for r in rows}
    dead = lambda rows: any(r["deadlock"] == "1" for r in rows)
    pb, pa = proj(before), proj(after)
    problems = []
    if pb != pa:
        problems.append(f"{len(pb - pa)} observed valuations lost, {len(pa - pb)} added")
    if not ignore and dead(before) != dead(after):
        problems.append(f"deadlock verdict {dead(before)} -> {dead(after)}")
    print(f"{model}: {len(before)} -> {len(after)} states, {len(pb)} observed "
          f"valuations over {len(cols)} columns: " + ("; ".join(problems) or "OK"))
    sys.exit(1 if problems else 0)


main()
