#!/usr/bin/env python3
"""Writes an ST program with `zones` independent zones of `width` Boolean
inputs each, plus start and stop (issue 70's limits test): a zone's guard is
the AND of its inputs, so splitting one state's inputs runs through about
(width + 1) ** zones classes while it has at most 3 ** zones successors."""
import sys

zones = int(sys.argv[1]) if len(sys.argv) > 1 else 8
width = int(sys.argv[2]) if len(sys.argv) > 2 else 5
print("PROGRAM Zones")
print("VAR_INPUT start : BOOL; stop : BOOL;")
for z in range(zones):
    print("  " + " ".join(f"i{z}_{k} : BOOL;" for k in range(width)))
print("END_VAR")
print("VAR_OUTPUT")
for z in range(zones):
    print(f"  Run{z} : BOOL;")
print("END_VAR")
print("VAR")
for z in range(zones):
    print(f"  Guard{z} : BOOL;")
print("END_VAR")
for z in range(zones):
    print(f"Guard{z} := " + " AND ".join(f"i{z}_{k}" for k in range(width)) + ";")
    print(f"IF start AND Guard{z} THEN Run{z} := TRUE; END_IF;")
    print(f"IF stop OR NOT Guard{z} THEN Run{z} := FALSE; END_IF;")
print("END_PROGRAM")
