#!/usr/bin/env python3
"""Cross-checks `netlift reach` against spin on the Promela export: for each
model, `netlift emit --to promela` is compiled by spin into a verifier (pan,
no partial-order reduction) and explored in full.

- States: pan's stored states, minus the offset the export's header line
  states, must equal netlift's states.
- Edges (place/transition encoding only, explored breadth-first): pan's
  transitions (stored + matched, which counts the initial state once more)
  must equal netlift's edges + 1. The step encoding makes one spin
  transition per (input valuation, choice) of a step, not per edge.
- Deadlocks (when the header says `deadlocks=end-states`): the `end` label
  is taken out, so a deadlock is an invalid end state for spin; spin finds
  one exactly when netlift counts deadlocks.
- Properties (each `--ctl FORMULA`, in the fragment of CTL the export
  writes as LTL): `netlift check` and spin's search for a violation of the
  `ltl` claim (acceptance cycles included) must give the same verdict.
With --bench, also prints both tools' speed and memory side by side, each
as the tool reports it (spin: pan's rate and its actual memory for states).

usage: check-spin.py [--bench] [--ctl FORMULA]... NETLIFT MODEL...
Prints one line per model and a closing 'N passed, M failed' line; exit 1
when some failed.
"""
import os
import re
import subprocess
import sys
import tempfile
import time

from crosscheck import Tally, netlift_summary, split_ctl


def header(pml):
    """The export's header: encoding, state offset, deadlock convention."""
    with open(pml) as f:
        first = f.readline()
    fields = dict(re.findall(r"(\w[\w-]*)=(\S+)", first))
    return {"encoding": fields.get("encoding", "transitions"),
            "offset": int(fields.get("state-offset", "0")),
            "deadlocks": fields.get("deadlocks", "end-states"),
            "stutter": fields.get("stutter", "none")}


def spin_run(pml, work, head, states, optimise):
    if head["deadlocks"] == "end-states":
        with open(pml) as f:
            text = f.read()
        with open(pml, "w") as f:
            f.write(re.sub(r"(?m)^end:\n", "", text))
    r = subprocess.run(["spin", "-a", pml], cwd=work, capture_output=True,
                       text=True)
    if r.returncode != 0:
        raise RuntimeError("spin -a: " + (r.stdout + r.stderr).strip()[:300])
    # No memory cap; compile time is not part of the figures, and only the
    # benchmark pays for an optimised verifier. The step encoding
    # keeps scratch variables `hidden`, which pan explores depth-first only.
    order = ["-DBFS"] if head["encoding"] == "transitions" else []
    r = subprocess.run(["cc", "-O2" if optimise else "-O0", "-fwrapv", *order,
                        "-DNOREDUCE",
                        "-DSAFETY", "-DMEMLIM=20000", "-o", "pan", "pan.c"],
                       cwd=work, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("cc: " + r.stderr.strip()[:300])
    # -c0: go on after an invalid end state (a deadlock) to count them all.
    # The search depth (-m) is a preallocated stack: start from what the
    # states and a few statements per atomic step need, grow when short.
    depth = 10000 + 50 * states
    hash_bits = max(16, min(26, (4 * states).bit_length()))
    for _ in range(3):
        start = time.monotonic()
        r = subprocess.run(["./pan", f"-w{hash_bits}", f"-m{depth}", "-c0"],
                           cwd=work,
                           capture_output=True, text=True, timeout=3600)
        elapsed = time.monotonic() - start
        out = r.stdout
        if "max search depth too small" not in out:
            break
        depth *= 8
    else:
        raise RuntimeError(f"pan: search depth {depth} too small")
    stored = re.search(r"(\d+) states, stored", out)
    trans = re.search(r"(\d+) transitions \(= stored\+matched\)", out)
    errors = re.search(r"errors: (\d+)", out)
    rate = re.search(r"pan: rate\s+([\d.e+]+) states/second", out)
    states_mb = re.search(r"([\d.]+)\s+actual memory usage for states", out)
    if not stored or not trans or not errors:
        raise RuntimeError("unexpected pan output:\n" + out[-2000:])
    asserts = "assertion violated" in out
    bound = "index out of range" in out or "out of range" in out
    return {"states": int(stored.group(1)) - head["offset"],
            "transitions": int(trans.group(1)),
            "errors": int(errors.group(1)),
            "assertion": asserts, "bound": bound,
            "seconds": elapsed,
            "rate": float(rate.group(1)) if rate else float("nan"),
            "state_mbytes": float(states_mb.group(1)) if states_mb
            else float("nan")}


def spin_properties(pml, work, count):
    """spin's verdict on each ltl claim p1..pN: True when it holds."""
    r = subprocess.run(["spin", "-a", pml], cwd=work, capture_output=True,
                       text=True)
    if r.returncode != 0:
        raise RuntimeError("spin -a: " + (r.stdout + r.stderr).strip()[:300])
    r = subprocess.run(["cc", "-O0", "-fwrapv", "-DNOREDUCE", "-o", "pan",
                        "pan.c"], cwd=work, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("cc: " + r.stderr.strip()[:300])
    verdicts = []
    for i in range(1, count + 1):
        # -a: acceptance cycles (liveness); -E: a deadlock is no violation
        # (the run stays there, as netlift's CTL takes it).
        r = subprocess.run(["./pan", "-a", "-E", "-m10000000", "-N",
                            f"p{i}"], cwd=work, capture_output=True,
                           text=True, timeout=3600)
        errors = re.search(r"errors: (\d+)", r.stdout)
        if not errors or "max search depth too small" in r.stdout:
            raise RuntimeError("unexpected pan output:\n" + r.stdout[-1000:])
        verdicts.append(int(errors.group(1)) == 0)
    return verdicts


def check_properties(netlift, model, name, ctl):
    """Compares netlift check's verdicts with spin's; returns ok."""
    with tempfile.TemporaryDirectory() as work:
        pml = os.path.join(work, "model.pml")
        flags = [a for f in ctl for a in ("--ctl", f)]
        e = subprocess.run([netlift, "emit", "--to", "promela", model, "-o",
                            pml, *flags], capture_output=True, text=True)
        if e.returncode != 0:
            print(f"FAIL {name}: emit: {e.stderr.strip()[:300]}")
            return False
        c = subprocess.run([netlift, "check", model, *flags],
                           capture_output=True, text=True)
        ours = re.findall(r"^(.*): (holds|fails)$", c.stdout, re.M)
        theirs = spin_properties(pml, work, len(ctl))
        stutter = header(pml)["stutter"] == "some"
    ok = len(ours) == len(ctl)
    for i, f in enumerate(ctl):
        mine = ours[i][1] == "holds" if i < len(ours) else None
        agree = mine == theirs[i]
        # Dropped steps are stutters netlift does not have: spin may find
        # a run that stays put forever, which only matters for liveness.
        if stutter and not agree and mine:
            print(f"skip {name}: {f}: netlift holds, spin fails on a"
                  " stutter of dropped steps (free inputs or urgent forced"
                  " transitions)")
            continue
        ok = ok and agree
        print(("ok   " if agree else "FAIL ") + f"{name}: {f}: netlift"
              f" {'holds' if mine else 'fails'}, spin"
              f" {'holds' if theirs[i] else 'fails'}")
    return ok


def main():
    ctl, args = split_ctl(sys.argv[1:])
    bench = "--bench" in args
    args = [a for a in args if a != "--bench"]
    netlift, models = args[0], args[1:]
    tally = Tally()
    for model in models:
        name = os.path.basename(os.path.dirname(model)) \
            if os.path.basename(model) == "model.pnml" else os.path.basename(model)
        with tempfile.TemporaryDirectory() as work:
            pml = os.path.join(work, "model.pml")
            e = subprocess.run([netlift, "emit", "--to", "promela", model,
                                "-o", pml], capture_output=True, text=True)
            if e.returncode != 0:
                tally.report(False, f"{name}: emit: {e.stderr.strip()[:300]}")
                continue
            # A runtime error of the model (write conflict, range...) stops
            # netlift; spin must fail an assertion or a bound check.
            ours = netlift_summary(netlift, model)
            runtime_error = ours is None
            head = header(pml)
            try:
                theirs = spin_run(pml, work, head,
                                  ours["states"] if ours else 100000, bench)
            except RuntimeError as err:
                tally.report(False, f"{name}: {err}")
                continue
        if ctl and not runtime_error:
            # check_properties prints a line per property.
            if check_properties(netlift, model, name, ctl):
                tally.passed += 1
            else:
                tally.failed += 1
        if runtime_error:
            ok = theirs["assertion"] or theirs["bound"]
            tally.report(ok, f"{name}: runtime error: netlift stops, spin"
                         f" {'fails' if ok else 'does not'}")
            continue
        steps = head["encoding"] == "steps"
        ok = (not theirs["assertion"] and ours["complete"]
              and theirs["states"] == ours["states"])
        line = f"{name}: netlift {ours['states']} states"
        if steps:
            line += f"; spin {theirs['states']} states"
        else:
            ok = ok and theirs["transitions"] == ours["transitions"] + 1
            line = (f"{name}: netlift {ours['states']} states"
                    f" {ours['transitions']} edges; spin {theirs['states']}"
                    f" states {theirs['transitions'] - 1} edges")
        if head["deadlocks"] == "end-states":
            ok = ok and (theirs["errors"] > 0) == (ours["deadlocks"] > 0)
            line += (f"; deadlocks: netlift {ours['deadlocks']},"
                     f" spin {'some' if theirs['errors'] else 'none'}")
        if bench:
            # Both figures as each tool reports them: states per second of
            # search, and bytes of stored states (with their index) per state;
            # spin's hash table (-w, sized to the states) is not counted.
            spin_bps = theirs["state_mbytes"] * 2**20 / max(theirs["states"], 1)
            line += (f"; netlift {ours['states_per_second']:.0f} states/s"
                     f" {ours['bytes_per_state']:.1f} B/state,"
                     f" spin {theirs['rate']:.0f} states/s"
                     f" {spin_bps:.1f} B/state; time netlift/spin"
                     f" {ours['seconds'] / max(theirs['seconds'], 1e-6):.2f}")
        tally.report(ok, line)
    return tally.finish()


if __name__ == "__main__":
    sys.exit(main())
