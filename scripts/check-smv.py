#!/usr/bin/env python3
"""Cross-checks netlift against its SMV export: for each model, `netlift
emit --to smv` is explored by scripts/smv-explore.py, an explicit reading
of SMV's semantics that shares no code with netlift (NuSMV and nuXmv are
not in Debian's archive; with one of them, the same file is its input).

- States: the SMV model's reachable states must be netlift's.
- Transitions: SMV's (pairs of states) must be netlift's distinct
  (source, target) pairs of edges plus one self-loop per deadlock.
- Deadlocks: the states where the `deadlock` DEFINE holds must be as many
  as netlift counts.
- Runtime errors: `INVARSPEC !netlift_error` must fail exactly when
  `netlift reach` stops at a runtime error.
- Properties (each `--ctl FORMULA`, an INVARSPEC when it is `AG p` over
  the state, else a CTLSPEC): the verdict must be `netlift check`'s.

usage: check-smv.py [--ctl FORMULA]... NETLIFT MODEL...
Prints one line per model and a closing 'N passed, M failed' line; exit 1
when some failed.
"""
import json
import os
import re
import subprocess
import sys
import tempfile

from crosscheck import Tally, netlift_summary, split_ctl

EXPLORE = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                       "smv-explore.py")


def netlift_pairs(netlift, model, work):
    """netlift's distinct (source, target) pairs of edges."""
    aut = os.path.join(work, "model.aut")
    subprocess.run([netlift, "reach", model, "--format", "aut", "-o", aut,
                    "-q"], capture_output=True, text=True)
    pairs = set()
    with open(aut) as f:
        for line in f:
            m = re.match(r"\((\d+),.*,(\d+)\)\s*$", line)
            if m:
                pairs.add((m.group(1), m.group(2)))
    return len(pairs)


def check(netlift, model, ctl):
    name = os.path.basename(model)
    flags = [a for f in ctl for a in ("--ctl", f)]
    with tempfile.TemporaryDirectory() as work:
        smv = os.path.join(work, "model.smv")
        e = subprocess.run([netlift, "emit", "--to", "smv", model, "-o", smv,
                            *flags], capture_output=True, text=True)
        if e.returncode != 0:
            return False, f"{name}: emit: {e.stderr.strip()[:300]}"
        x = subprocess.run([sys.executable, EXPLORE, smv, "--json", "--count",
                            "deadlock"], capture_output=True, text=True)
        if x.returncode != 0:
            return False, f"{name}: {x.stderr.strip()[:300]}"
        theirs = json.loads(x.stdout)
        ours = netlift_summary(netlift, model)
        if ours is None:
            ok = not theirs["specs"][0]
            return ok, (f"{name}: runtime error: netlift stops, INVARSPEC "
                        f"!netlift_error {'fails' if ok else 'holds'}")
        pairs = netlift_pairs(netlift, model, work)
    edges = pairs + ours["deadlocks"]
    ok = (ours["complete"] and theirs["states"] == ours["states"]
          and theirs["transitions"] == edges
          and theirs["deadlock"] == ours["deadlocks"]
          and theirs["specs"][0])
    line = (f"{name}: netlift {ours['states']} states {edges} pairs"
            f" {ours['deadlocks']} deadlocks; smv {theirs['states']} states"
            f" {theirs['transitions']} pairs {theirs['deadlock']} deadlocks")
    if ctl:
        c = subprocess.run([netlift, "check", model, *flags],
                           capture_output=True, text=True)
        verdicts = [v == "holds" for v in
                    re.findall(r"^.*: (holds|fails)$", c.stdout, re.M)]
        same = verdicts == theirs["specs"][1:]
        ok = ok and same
        line += "; ctl " + ("agree" if same else "DIFFER") + " (" + " ".join(
            "holds" if v else "fails" for v in theirs["specs"][1:]) + ")"
    return ok, line


def main():
    ctl, args = split_ctl(sys.argv[1:])
    netlift, models = args[0], args[1:]
    tally = Tally()
    for model in models:
        tally.report(*check(netlift, model, ctl))
    return tally.finish()


if __name__ == "__main__":
    sys.exit(main())
