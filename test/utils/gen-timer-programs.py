#!/usr/bin/env python3
"""Writes random ST programs with timers (TON, TOF, TP) for the soundness
oracle of --timers=abstract (abstract-covers-exact.py): inputs, timers fed
by inputs and by each other's outputs, a latch and a small counter driven
by their outputs, a timer whose ET is read now and then.

usage: gen-timer-programs.py SEED COUNT DIR
"""
import os
import random
import sys


def program(rng, k):
    n_in = rng.randint(1, 3)
    n_t = rng.randint(1, 3)
    ins = [f"b{i}" for i in range(n_in)]
    lines = [f"PROGRAM Timers{k}",
             "  VAR_INPUT " + ", ".join(ins) + " : BOOL; END_VAR",
             "  VAR_OUTPUT q, latch : BOOL; n : INT; END_VAR"]
    decls = [f"t{i} : {rng.choice(['TON', 'TOF', 'TP'])};" for i in range(n_t)]
    lines.append("  VAR " + " ".join(decls) + " END_VAR")
    signals = list(ins)
    for i in range(n_t):
        src = rng.choice(signals)
        if rng.random() < 0.3:
            src = f"NOT {src}"
        if rng.random() < 0.3:
            src = f"{src} AND {rng.choice(ins)}"
        pt = rng.randint(0, 4) * 100
        lines.append(f"  t{i}(IN := {src}, PT := T#{pt}ms);")
        signals.append(f"t{i}.Q")
    outs = signals[n_in:]
    lines.append(f"  q := {' OR '.join(rng.sample(outs, rng.randint(1, len(outs))))};")
    set_ = rng.choice(outs)
    reset = rng.choice(ins)
    lines.append(f"  IF {set_} THEN latch := TRUE; END_IF;")
    lines.append(f"  IF {reset} AND NOT {set_} THEN latch := FALSE; END_IF;")
    lines.append(f"  IF {rng.choice(outs)} AND n < 3 THEN n := n + 1; "
                 f"ELSIF {rng.choice(ins)} THEN n := 0; END_IF;")
    if rng.random() < 0.3:
        lines.append(f"  IF t0.ET > T#100ms THEN n := 0; END_IF;")
    lines.append("END_PROGRAM")
    lines += ["CONFIGURATION C RESOURCE R ON PLC",
              "  TASK cyc(INTERVAL := T#100ms, PRIORITY := 1);",
              f"  PROGRAM main WITH cyc : Timers{k};",
              "END_RESOURCE END_CONFIGURATION"]
    return "\n".join(lines) + "\n"


def main():
    seed, count, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    rng = random.Random(seed)
    os.makedirs(out, exist_ok=True)
    for k in range(count):
        with open(os.path.join(out, f"timers{k:02d}.st"), "w") as f:
            f.write(program(rng, k))


if __name__ == "__main__":
    main()
