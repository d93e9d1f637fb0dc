#!/usr/bin/env python3
"""Writes a Structured Text program whose data is reached through
references: N stations, each a function block holding a REF_TO to its own
counter and to a shared one: N + 1 places of type INT(0..3), each its own
family (the worst case: every dereference selects over all of them),
every station reading and writing through both references.
With --index the same program uses the variables directly (the oracle of
bench/ref-bench.sh: same state space).
usage: gen-refs.py STATIONS [--index] > refs.st"""
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 100
index = "--index" in sys.argv
out = sys.stdout
out.write("FUNCTION_BLOCK Station\n")
if index:
    out.write("  VAR_IN_OUT own : INT; shared : INT; END_VAR\n")
else:
    out.write("  VAR_INPUT own : REF_TO INT; shared : REF_TO INT; END_VAR\n")
out.write("  VAR_INPUT go : BOOL; END_VAR\n")
d = "" if index else "^"
out.write(f"""  IF go THEN
    own{d} := (own{d} + 1) MOD 4;
    IF own{d} = 0 THEN shared{d} := (shared{d} + 1) MOD 4; END_IF;
  END_IF;
END_FUNCTION_BLOCK
PROGRAM Refs
  VAR_INPUT sel : INT(0..{n - 1}); go : BOOL; END_VAR
  VAR
    total : INT(0..3);
""")
for i in range(n):
    out.write(f"    c{i} : INT(0..3);\n")
for i in range(n):
    out.write(f"    s{i} : Station;\n")
out.write("  END_VAR\n")
for i in range(n):
    if index:
        out.write(f"  s{i}(own := c{i}, shared := total, go := go AND sel = {i});\n")
    else:
        out.write(f"  s{i}(own := REF(c{i}), shared := REF(total), go := go AND sel = {i});\n")
out.write("END_PROGRAM\n")
