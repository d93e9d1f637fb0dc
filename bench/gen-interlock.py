#!/usr/bin/env python3
"""Writes a machine interlock in Structured Text with N Boolean inputs
(N/2 guard switches, N/2 start requests) whose successor count per state is
small: the machine runs while every guard is closed and some request came,
stops when a guard opens, a timer delays the ready lamp, and the scans
run are counted (modulo 1000). The benchmark
family of input splitting (bench/inputs-bench.sh).

usage: gen-interlock.py N > interlock.st"""
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 8
half = max(1, n // 2)
guards = ["guard%d" % i for i in range(half)]
requests = ["request%d" % i for i in range(n - half)]
out = sys.stdout
out.write("PROGRAM Interlock\n  VAR_INPUT\n")
for name in guards + requests:
    out.write("    %s : BOOL;\n" % name)
out.write("  END_VAR\n")
out.write("  VAR_OUTPUT motor, ready : BOOL; END_VAR\n")
out.write("  VAR closed : BOOL; settle : TON; runs : INT(0..999); END_VAR\n")
out.write("  closed := %s;\n" % " AND ".join(guards))
out.write("  IF closed THEN\n")
out.write("    IF %s THEN motor := TRUE; END_IF;\n" %
          (" OR ".join(requests) if requests else "TRUE"))
out.write("  ELSE\n    motor := FALSE;\n  END_IF;\n")
out.write("  settle(IN := motor, PT := T#3ms);\n")
out.write("  ready := settle.Q;\n")
# Scans run, counted while the motor runs: states enough to time.
out.write("  IF motor THEN runs := (runs + 1) MOD 1000; END_IF;\nEND_PROGRAM\n")
