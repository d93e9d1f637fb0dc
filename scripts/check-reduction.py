#!/usr/bin/env python3
"""Checks a reduction by exploration: the state space of MODEL (flattened)
and of MODEL after PIPELINE, projected on the observed columns, must have
the same set of valuations, and the same deadlock verdict unless
--ignore-deadlocks (reduce-coi does not preserve deadlocks of the removed
part).

  check-reduction.py NETLIFT MODEL PIPELINE [--observe a,b,...] [--ignore-deadlocks]
                     [--same-graph]

Observed columns default to every column the reduced state space still has
(the original's with --same-graph) except clocks (clock readings are what reduce-clocks merges). Prints one
line: the state counts before and after, the number of observed
valuations, and OK or what differs; exits 1 when they differ.

--same-graph also requires the two labelled state graphs (.aut) to be
identical, states being named by their values in every column of the
original, and each step by the set of its transitions' names without a
copy suffix `_N` and without transitions the original does not have
(lower-data splits a transition `t` into copies `t_1`, `t_2`, ... and adds
forced setters to its steps): the check for passes that change the
representation, not the behaviour."""
import csv, io, re, subprocess, sys


def run_reach(netlift, model, pipeline, fmt):
    cmd = [netlift, "opt", model, "-p", "flatten" + ("," + pipeline if pipeline else "")]
    net = subprocess.run(cmd, capture_output=True, text=True)
    if net.returncode:
        sys.exit(f"check-reduction: {' '.join(cmd)} failed:\n{net.stderr}")
    out = subprocess.run([netlift, "reach", "-", "--format", fmt, "-q"],
                         input=net.stdout, capture_output=True, text=True)
    if out.returncode not in (0,):
        sys.exit(f"check-reduction: reach failed:\n{out.stderr}")
    return out.stdout


def explore(netlift, model, pipeline=None):
    return list(csv.DictReader(io.StringIO(run_reach(netlift, model, pipeline, "csv"))))


def graph(netlift, model, pipeline, cols):
    """The .aut edges between states named by their values in `cols`
    (so that a different exploration order does not matter); a step label
    becomes the set of its transitions' names without copy suffixes."""
    rows = explore(netlift, model, pipeline)
    for c in cols:
        if rows and c not in rows[0]:
            sys.exit(f"check-reduction: '{c}' is not a column of {pipeline or 'the original'} state space")
    name = {r["id"]: tuple(r[c] for c in cols) for r in rows}
    edges = set()
    for line in run_reach(netlift, model, pipeline, "aut").splitlines()[1:]:
        src, rest = line[1:-1].split(",", 1)
        label, dst = rest.rsplit(",", 1)
        label = label.strip('"')
        if label.startswith("{"):
            label = frozenset(re.sub(r"_[0-9]+$", "", n) for n in label[1:-1].split(","))
        edges.add((name[src], label, name[dst]))
    return edges


def same_steps(before, after):
    """`after` with each step keeping only the transitions the original
    steps name (lower-data adds forced setters to the steps)."""
    known = set().union(*(l for _, l, _ in before if isinstance(l, frozenset)))
    return {(s, l & known if isinstance(l, frozenset) else l, d) for s, l, d in after}


def main():
    args = sys.argv[1:]
    ignore = "--ignore-deadlocks" in args
    same_graph = "--same-graph" in args
    args = [a for a in args if a not in ("--ignore-deadlocks", "--same-graph")]
    observe = None
    if "--observe" in args:
        i = args.index("--observe")
        observe = args[i + 1].split(",")
        del args[i:i + 2]
    netlift, model, pipeline = args
    before = explore(netlift, model)
    after = explore(netlift, model, pipeline)
    # By default: what the reduced model keeps, or with --same-graph (which
    # renames rather than removes) what the original has.
    base = before if same_graph else after
    cols = observe or [c for c in (base[0].keys() if base else [])
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
    if same_graph:
        # States are named by every column of the original.
        full = [c for c in before[0].keys() if c not in ("id", "deadlock")] if before else []
        gb = graph(netlift, model, None, full)
        ga = same_steps(gb, graph(netlift, model, pipeline, full))
        if gb != ga:
            problems.append(f"state graphs differ ({len(gb - ga)} edges lost, "
                            f"{len(ga - gb)} added)")
    if not ignore and dead(before) != dead(after):
        problems.append(f"deadlock verdict {dead(before)} -> {dead(after)}")
    print(f"{model}: {len(before)} -> {len(after)} states, {len(pb)} observed "
          f"valuations over {len(cols)} columns: " + ("; ".join(problems) or "OK"))
    sys.exit(1 if problems else 0)


main()
