#!/usr/bin/env python3
"""Writes small random ST programs whose free inputs are read in every way
input splitting distinguishes (docs/semantics.md, "Free inputs"): Boolean
inputs tested and combined, integer inputs compared with constants and with
state, compared with each other, under arithmetic, as CASE selectors, as
array indices, stored into state, fed to timers and edge detectors. The
state stays small, so that every program also explores with every valuation
enumerated: split-vs-enumerate.py compares the two.

usage: gen-input-programs.py SEED COUNT DIR
"""
import os
import random
import sys


def program(rng, index):
    nb = rng.randint(2, 7)
    ni = rng.randint(1, 3)
    bools = ["b%d" % i for i in range(nb)]
    ints = ["i%d" % i for i in range(ni)]
    ranges = {}
    lines = ["PROGRAM Gen%d" % index, "  VAR_INPUT"]
    for b in bools:
        lines.append("    %s : BOOL;" % b)
    valuations = 2 ** nb
    for i in ints:
        lo = rng.randint(-6, 2)
        hi = lo + rng.randint(2, 24)
        # Few enough valuations that enumerating them stays quick.
        while valuations * (hi - lo + 1) > 4000 and hi > lo + 1:
            hi -= 1
        valuations *= hi - lo + 1
        ranges[i] = (lo, hi)
        if rng.random() < 0.5:
            lines.append("    {range %d..%d} %s : INT;" % (lo, hi, i))
        else:
            lines.append("    %s : INT(%d..%d);" % (i, lo, hi))
    lines += ["  END_VAR",
              "  VAR_OUTPUT q0, q1 : BOOL; END_VAR",
              "  VAR",
              "    s : INT(0..5);",
              "    m : INT(-40..40);",
              "    arr : ARRAY[0..3] OF BOOL;",
              "    t : TON; e : R_TRIG;",
              "  END_VAR"]

    def b():
        return rng.choice(bools)

    def i():
        return rng.choice(ints)

    def const(name):
        lo, hi = ranges[name]
        return rng.randint(lo - 2, hi + 2)

    def cond(depth=0):
        k = rng.randint(0, 9 if depth < 2 else 5)
        if k == 0:
            return b()
        if k == 1:
            return "NOT " + b()
        if k == 2:
            x = i()
            return "%s %s %d" % (x, rng.choice(["<", "<=", ">", ">=", "=",
                                                "<>"]), const(x))
        if k == 3:
            return "%s > s" % i()
        if k == 4:
            return "(%s * %d + %d) %s %d" % (i(), rng.choice([-3, -1, 2, 5]),
                                             rng.randint(-4, 4),
                                             rng.choice(["<", ">=", "="]),
                                             rng.randint(-10, 10))
        if k == 5:
            return "q%d" % rng.randint(0, 1)
        if k == 6:
            return "(%s %s %s)" % (cond(depth + 1),
                                   rng.choice(["AND", "OR", "XOR"]),
                                   cond(depth + 1))
        if k == 7:
            return "%s < %s" % (i(), i())
        if k == 8:
            return "(%s MOD 3) = %d" % (i(), rng.randint(0, 2))
        return "NOT (%s)" % cond(depth + 1)

    def stmt(depth=0):
        k = rng.randint(0, 9 if depth < 2 else 4)
        if k == 0:
            return ["q%d := %s;" % (rng.randint(0, 1), cond())]
        if k == 1:
            return ["s := (s + 1) MOD 6;"]
        if k == 2:
            x = i()
            return ["m := LIMIT(-40, %s, 40);" % x]
        if k == 3:
            return ["arr[(%s MOD 4 + 4) MOD 4] := %s;" % (i(), cond())]
        if k == 4:
            return ["q0 := arr[s MOD 4] OR %s;" % b()]
        if k == 5:
            out = ["IF %s THEN" % cond()]
            out += ["  " + l for l in stmt(depth + 1)]
            if rng.random() < 0.6:
                out.append("ELSE")
                out += ["  " + l for l in stmt(depth + 1)]
            out.append("END_IF;")
            return out
        if k == 6:
            x = i()
            lo, hi = ranges[x]
            a = rng.randint(lo, hi)
            c = rng.randint(lo, hi)
            out = ["CASE %s OF" % x,
                   "  %d: s := 0;" % a,
                   "  %d..%d: s := %d;" % (min(a, c) - 1, max(a, c) + 1,
                                          rng.randint(1, 5))]
            out.append("ELSE")
            out += ["  " + l for l in stmt(depth + 1)]
            out.append("END_CASE;")
            return out
        if k == 7:
            return ["t(IN := %s, PT := T#%dms);" % (cond(), rng.choice([1, 2])),
                    "q1 := t.Q;"]
        if k == 8:
            return ["e(CLK := %s);" % b(),
                    "IF e.Q THEN s := 0; END_IF;"]
        return ["m := %s - %s;" % (i(), i())]

    body = []
    for _ in range(rng.randint(2, 5)):
        body += stmt()
    lines += ["  " + l for l in body]
    lines.append("END_PROGRAM")
    return "\n".join(lines) + "\n"


def main():
    seed, count, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    rng = random.Random(seed)
    os.makedirs(out, exist_ok=True)
    for n in range(count):
        with open(os.path.join(out, "gen%02d.st" % n), "w") as f:
            f.write(program(rng, n))


if __name__ == "__main__":
    main()
