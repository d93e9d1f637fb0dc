#!/usr/bin/env python3
"""Writes a large, realistic Structured Text program: N interlocked
stations, each a CASE sequencer with timers, counters, edges and
arithmetic. usage: gen-st.py STATIONS > big.st"""
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
out = sys.stdout
out.write("TYPE Phase : (Idle, Run, Hold, Done); END_TYPE\n")
out.write("PROGRAM Big\n  VAR_INPUT\n")
for i in range(n):
    out.write(f"    start{i}, sensor{i} : BOOL;\n")
out.write("  END_VAR\n  VAR_OUTPUT\n")
for i in range(n):
    out.write(f"    motor{i}, lamp{i} : BOOL;\n")
out.write("  END_VAR\n  VAR\n")
for i in range(n):
    out.write(f"    step{i} : Phase; t{i} : TON; c{i} : CTU; "
              f"e{i} : R_TRIG; n{i} : INT(0..100);\n")
out.write("  END_VAR\n")
for i in range(n):
    prev = f"motor{i - 1}" if i else "FALSE"
    out.write(f"""  e{i}(CLK := sensor{i});
  t{i}(IN := step{i} = Run, PT := T#{(i % 7) + 1}s);
  c{i}(CU := e{i}.Q, R := step{i} = Idle, PV := 3);
  CASE step{i} OF
    Idle: IF start{i} AND NOT {prev} THEN step{i} := Run; END_IF;
    Run:  IF t{i}.Q THEN step{i} := Hold; ELSIF c{i}.Q THEN step{i} := Done; END_IF;
    Hold: IF NOT sensor{i} THEN step{i} := Done; END_IF;
    Done: step{i} := Idle; n{i} := (n{i} + 1) MOD 100;
  END_CASE;
  motor{i} := step{i} = Run OR step{i} = Hold;
  lamp{i} := (n{i} > 50) XOR c{i}.Q;
""")
out.write("END_PROGRAM\n")
