#!/usr/bin/env python3
"""An independent oracle for `discretise`: simulates a hybrid NetIR model
(canonical text, as `netlift translate` prints it) by brute force in exact
rational arithmetic, with time in steps of DT ticks and every transition
tried at every step, and checks that every combination of marked
locations and cond output values the simulation reaches is also reached by
the discretised model (`netlift reach --format json`). The discretisation
over-approximates positions between grid points, so the simulation's set
must be a subset; the script says how many combinations only the
discretisation reaches.

Covers rectangular models: constant rates and rectangular flows `x' in
[a, b]` (each time step at rate a or b: every position a run at those
rates reaches), guards, invariants (`false`:
an urgent location, left in the instant it is entered) and outputs
built from comparisons of one real with a constant (and/or/not, places),
resets to constants, intervals (`between(a, b)`) or expressions of reals
(run in order, each reading what earlier ones set), initial values or
intervals (intervals sampled every DT).
A real may not leave its declared range (time stops there). With HORIZON,
runs stop at that time (in ticks): a model whose reals grow without bound
is simulated up to it.

usage: simulate-hybrid.py NETLIFT HYBRID.net DISCRETISED.net [DT] [MAX_STATES] [HORIZON]
exit: 0 subset, 1 a combination the discretisation misses, 2 unsupported
"""
import json
import re
import subprocess
import sys
from fractions import Fraction

NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_.]*")
WORDS = {"and", "or", "not", "true", "false"}


def unsupported(what):
    print(f"simulate-hybrid: unsupported: {what}", file=sys.stderr)
    sys.exit(2)


def compile_expr(text):
    """NetIR expression text -> a Python expression over V[name]."""
    def name(m):
        w = m.group(0)
        if w == "true":
            return "True"
        if w == "false":
            return "False"
        if w in WORDS:
            return w
        return f"V[{w!r}]"
    # Literals become exact fractions; names are looked up.
    out, pos = [], 0
    for m in re.finditer(r"\d+(\.\d+)?(e[-+]?\d+)?|[A-Za-z_][A-Za-z0-9_.]*",
                         text):
        out.append(text[pos:m.start()])
        tok = m.group(0)
        out.append(f"Fraction('{tok}')" if tok[0].isdigit() else
                   name(m))
        pos = m.end()
    out.append(text[pos:])
    return "".join(out)


def parse(text):
    model = {"reals": {}, "places": {}, "outputs": {}, "trans": [],
             "flows": {}, "invariants": {}}
    body = text[text.index("{") + 1:text.rindex("}")]
    for m in re.finditer(r"real (\S+) : \[([^,]+), ([^\]]+)\]"
                         r"(?: = ([^;]+)| in \[([^,]+), ([^\]]+)\])?;", body):
        def bound(t):
            return None if t.strip().lstrip("-") == "inf" else Fraction(t)
        lo, hi = bound(m.group(2)), bound(m.group(3))
        if m.group(4):
            init = (Fraction(m.group(4)), Fraction(m.group(4)))
        elif m.group(5):
            init = (bound(m.group(5)), bound(m.group(6)))
            if None in init:
                unsupported(f"real {m.group(1)} starts anywhere")
        else:
            init = (lo or Fraction(0), lo or Fraction(0))
        model["reals"][m.group(1)] = (lo, hi, init)
    for m in re.finditer(r"^\s*place (.+);$", body, re.M):
        for p in m.group(1).split(","):
            pm = re.match(r"\s*(\S+?)(?:\((\d+)\))?\s*$", p)
            model["places"][pm.group(1)] = int(pm.group(2) or 0)
    for m in re.finditer(r"cond output (\S+) = ([^;]+);", body):
        model["outputs"][m.group(1)] = compile_expr(m.group(2))
    for m in re.finditer(r"^\s*trans (\S+) : (.*?) -> (.*?)"
                         r"(?: guard (.*?))?( urgent)?(;|\s*\{(.*?)\})",
                         body, re.M | re.S):
        pre = [p.strip() for p in m.group(2).split(",")]
        post = [p.strip() for p in m.group(3).split(",")]
        if any(re.search(r"[\[\*]", p) for p in pre + post):
            unsupported(f"arc weights or times in transition {m.group(1)}")
        resets = []
        for a in re.finditer(r"(\S+) := ([^;]+);", m.group(7) or ""):
            # A reset to an interval: (target, (lo, hi)).
            iv = re.fullmatch(r"between\(([^,]+), ([^)]+)\)", a.group(2))
            if iv and "inf" in iv.group(0):
                unsupported(f"a reset to an interval open on one side in {m.group(1)}")
            resets.append((a.group(1),
                           (Fraction(iv.group(1)), Fraction(iv.group(2)))
                           if iv else compile_expr(a.group(2))))
        model["trans"].append((m.group(1), pre, post,
                               compile_expr(m.group(4) or "true"), resets,
                               bool(m.group(5))))
    for m in re.finditer(r"flow (\S+) \{(.*?)\}", body):
        rates = {}
        # x' = r, or a rectangular flow x' in [a, b]: (a, b).
        for e in re.finditer(r"(\S+)' (?:= ([^;]+)|in \[([^,]+), ([^\]]+)\]);",
                             m.group(2)):
            try:
                if e.group(2):
                    rate = Fraction(e.group(2).strip())
                    rates[e.group(1)] = (rate, rate)
                else:
                    rates[e.group(1)] = (Fraction(e.group(3).strip()),
                                         Fraction(e.group(4).strip()))
            except ValueError:
                unsupported(f"rate {e.group(0)} (constant rates only)")
        model["flows"][m.group(1)] = rates
    model["urgent"] = set()
    for m in re.finditer(r"invariant (\S+) \{(.*?)\}", body):
        conds = [c.strip() for c in m.group(2).split(";") if c.strip()]
        # `false`: an urgent location (no time passes there; it may be
        # entered), not a condition its states must meet.
        if "false" in conds:
            model["urgent"].add(m.group(1))
        model["invariants"][m.group(1)] = [
            compile_expr(c) for c in conds if c != "false"]
    return model


def simulate(model, dt, max_states, horizon):
    reals = list(model["reals"])
    places = list(model["places"])
    env = {"Fraction": Fraction}

    def holds(expr, marking, values):
        v = dict(zip(reals, values))
        v.update({p: p in marking for p in places})
        return eval(expr, env, {"V": v})

    def invariant_ok(marking, values):
        for i, (lo, hi, _) in enumerate(model["reals"].values()):
            if (lo is not None and values[i] < lo) or \
                    (hi is not None and values[i] > hi):
                return False
        return all(holds(c, marking, values) for p in marking
                   for c in model["invariants"].get(p, []))

    starts = [[]]
    for name in reals:
        a, b = model["reals"][name][2]
        samples = sorted({a, b} | {a + k * dt for k in range(int((b - a) / dt) + 1)})
        starts = [s + [x] for s in starts for x in samples]
    marking0 = frozenset(p for p, n in model["places"].items() if n)
    seen = set()
    work = []
    # A state is (marking, values, time): time stays 0 without a horizon.
    for s in starts:
        st = (marking0, tuple(s), Fraction(0))
        if invariant_ok(*st[:2]) and st not in seen:
            seen.add(st)
            work.append(st)
    while work:
        marking, values, now = work.pop()
        succ = []
        urgent = False
        for name, pre, post, guard, resets, is_urgent in model["trans"]:
            if not all(p in marking for p in pre) or \
                    not holds(guard, marking, values):
                continue
            urgent |= is_urgent
            # Every combination of the reset values (an interval sampled
            # every DT, its ends included). Statements run in order: each
            # reads the values the action's earlier ones set.
            news = [dict(zip(reals, values))]
            for target, expr in resets:
                if isinstance(expr, tuple):
                    lo, hi = expr
                    choices = sorted({lo, hi} | {lo + k * dt for k in
                                                 range(int((hi - lo) / dt) + 1)})
                    news = [{**n, target: c} for n in news for c in choices]
                else:
                    news = [{**n, target: holds(expr, marking,
                                                tuple(n[r] for r in reals))}
                            for n in news]
            m2 = (marking - set(pre)) | set(post)
            for new in news:
                v2 = tuple(new[r] for r in reals)
                if invariant_ok(m2, v2):
                    succ.append((m2, v2, now))
        urgent |= any(p in model["urgent"] for p in marking)
        if not urgent and (horizon is None or now + dt <= horizon):
            rate = {r: (Fraction(0), Fraction(0)) for r in reals}
            for p in marking:
                rate.update(model["flows"].get(p, {}))
            # A rectangular flow may take any rate in its interval at any
            # instant: each step takes one of its two ends.
            moves = [()]
            for r in reals:
                moves = [mv + (x,) for mv in moves for x in sorted(set(rate[r]))]
            for mv in moves:
                v2 = tuple(values[i] + mv[i] * dt for i in range(len(reals)))
                if invariant_ok(marking, v2):
                    succ.append((marking, v2,
                                 now + dt if horizon is not None else now))
        for st in succ:
            if st not in seen:
                seen.add(st)
                work.append(st)
                if len(seen) > max_states:
                    unsupported(f"more than {max_states} simulated states")
    outputs = list(model["outputs"])
    return {(tuple(sorted(m)),
             tuple(bool(holds(model["outputs"][o], m, v)) for o in outputs))
            for m, v, _ in seen}, places, outputs


def main():
    if len(sys.argv) < 4:
        print(__doc__.strip().splitlines()[-2], file=sys.stderr)
        return 2
    netlift, hybrid, discretised = sys.argv[1:4]
    dt = Fraction(sys.argv[4]) if len(sys.argv) > 4 else Fraction(1, 4)
    max_states = int(sys.argv[5]) if len(sys.argv) > 5 else 200000
    horizon = Fraction(sys.argv[6]) if len(sys.argv) > 6 else None
    model = parse(open(hybrid).read())
    sim, places, outputs = simulate(model, dt, max_states, horizon)
    graph = json.loads(subprocess.run(
        [netlift, "reach", discretised, "--format", "json", "-o", "-"],
        check=True, capture_output=True, text=True).stdout)
    names = [a["name"] for a in graph["attributes"]]
    pcols = [(p, names.index(p)) for p in places if p in names]
    ocols = [names.index(o) for o in outputs]
    disc = {(tuple(sorted(p for p, c in pcols if s["values"][c])),
             tuple(bool(s["values"][c]) for c in ocols))
            for s in graph["states"]}
    missing = sorted(sim - disc)
    label = f"{len(sim)} location/output combinations simulated (dt {dt})"
    if missing:
        print(f"MISSING {label}; the discretisation misses {len(missing)}:")
        for m in missing:
            print(f"  {m}")
        return 1
    print(f"ok {label}, all reached by the discretisation "
          f"({len(disc - sim)} more only there)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
