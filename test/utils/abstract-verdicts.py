#!/usr/bin/env python3
"""The verdicts of `reach --find P --timers=abstract` (with its replay,
exact search and refinement) against `--timers=exact`: the same answer
(found: exit 0, none: exit 3) or undecided (exit 2), never the other
answer. Prints a count per outcome; exits 1 on a disagreement.

usage: abstract-verdicts.py NETLIFT [--replay-states N] --list FILE PRED...
"""
import subprocess
import sys


def code(netlift, args):
    return subprocess.run([netlift, "reach", *args, "--inputs=split"],
                          capture_output=True, text=True,
                          timeout=300).returncode


def main():
    args = sys.argv[1:]
    netlift = args.pop(0)
    extra, models, preds = [], [], []
    while args:
        a = args.pop(0)
        if a == "--replay-states":
            extra += ["--replay-states", args.pop(0)]
        elif a == "--list":
            models += [l.strip() for l in open(args.pop(0)) if l.strip()]
        else:
            preds.append(a)
    counts = {"same": 0, "undecided": 0, "DIFFERENT": 0}
    for model in models:
        for p in preds:
            exact = code(netlift, [model, "--find", p])
            if exact not in (0, 3):
                continue
            abstract = code(netlift, [model, "--find", p, "--timers=abstract",
                                      *extra])
            if abstract == exact:
                counts["same"] += 1
            elif abstract == 2:
                counts["undecided"] += 1
            else:
                counts["DIFFERENT"] += 1
                print(f"DIFFERENT {model} '{p}': exact exit {exact}, "
                      f"abstract exit {abstract}")
    print("verdicts: " + ", ".join(f"{v} {k}" for k, v in counts.items()))
    return 1 if counts["DIFFERENT"] else 0


if __name__ == "__main__":
    sys.exit(main())
