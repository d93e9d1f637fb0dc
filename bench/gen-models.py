#!/usr/bin/env python3
"""Scalable NetIR models for the state-space benchmark.

usage: gen-models.py KIND N > model.net
  philosophers N   dining philosophers, 1-safe P/T net (no data)
  ring N           token ring of N stations with a counter each (data)
  prodcons N       timed producer/consumer, buffer of capacity N (time)
  closedloop N     controller scan cycle with a timer and data, and N
                   cylinders as plant (closed loop: data, clocks, events)
"""
import sys


def philosophers(n):
    out = ["system Philosophers {"]
    for i in range(n):
        out.append(f"  place think{i}(1), fork{i}(1), left{i}, eat{i};")
    for i in range(n):
        j = (i + 1) % n
        out.append(f"  trans takeLeft{i} : think{i}, fork{i} -> left{i};")
        out.append(f"  trans takeRight{i} : left{i}, fork{j} -> eat{i};")
        out.append(f"  trans release{i} : eat{i} -> think{i}, fork{i}, fork{j};")
    out.append("}")
    return "\n".join(out)


def ring(n):
    out = ["system Ring {"]
    for i in range(n):
        out.append(f"  var count{i} : 0..3;")
    for i in range(n):
        tok = "(1)" if i == 0 else ""
        out.append(f"  place tok{i}{tok}, busy{i};")
    for i in range(n):
        j = (i + 1) % n
        out.append(f"  trans work{i} : tok{i} -> busy{i} {{ count{i} := (count{i} + 1) % 4; }}")
        out.append(f"  trans pass{i} : busy{i} -> tok{j};")
        out.append(f"  trans skip{i} : tok{i} -> tok{j} guard count{i} == 3;")
    out.append("}")
    return "\n".join(out)


def prodcons(n):
    return f"""system ProdCons {{
  place ready(1), buf cap {n}, idle(1), busy;
  trans produce : ready[1,3] -> ready, buf;
  trans take : idle, buf -> busy;
  trans done : busy[2,4] -> idle;
}}"""


def closedloop(n):
    lines = ["module Cylinder {", "  event input extend, retract;",
             "  cond output at_home = home, at_end = end;",
             "  place home(1), out, end, back;",
             "  trans go : home -> out on extend;",
             "  trans arrive : out[2,3] -> end;",
             "  trans ret : end -> back on retract;",
             "  trans arriveHome : back[2,3] -> home;", "}",
             "module Ctrl {", "  cond input " + ", ".join(f"e{i}, h{i}" for i in range(n)) + ";",
             "  event output " + ", ".join(f"x{i}, r{i}" for i in range(n)) + ";",
             "  var step : 0..%d;" % (2 * n), "  var cycles : 0..7;",
             "  clock t : 0..10;", "  place cycle(1);",
             "  trans scan : cycle[1,1] -> cycle urgent {",
             "    if t >= 2 { t := 0; cycles := (cycles + 1) % 8; }", "  }"]
    for i in range(n):
        lines.append(f"  trans ext{i} : cycle -> cycle guard step == {2*i} and h{i} emit x{i} {{ step := {2*i+1}; }}")
        nxt = (2 * i + 2) % (2 * n)
        lines.append(f"  trans ret{i} : cycle -> cycle guard step == {2*i+1} and e{i} emit r{i} {{ step := {nxt}; }}")
    lines.append("}")
    lines.append("system Closed {")
    lines.append("  inst c : Ctrl;")
    for i in range(n):
        lines.append(f"  inst p{i} : Cylinder;")
        lines.append(f"  connect c.x{i} -> p{i}.extend; connect c.r{i} -> p{i}.retract;")
        lines.append(f"  connect p{i}.at_end -> c.e{i}; connect p{i}.at_home -> c.h{i};")
    lines.append("}")
    return "\n".join(lines)


if __name__ == "__main__":
    kind, n = sys.argv[1], int(sys.argv[2])
    print({"philosophers": philosophers, "ring": ring, "prodcons": prodcons,
           "closedloop": closedloop}[kind](n))
