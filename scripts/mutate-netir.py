#!/usr/bin/env python3
"""Robustness sweep: feed netlift mutated input files (NetIR, Structured
Text, Instruction List, ...: the mutated file keeps its input's extension)
and require that each run ends with exit code 0 or 1, never a crash, a
sanitizer report or a hang.

usage: mutate-netir.py NETLIFT SEED COUNT [-I DIR] [--fb-semantics M] FILE...
(-I DIR: a type library for translate, e.g. the inputs' own directory, so
that a mutated IEC 61499 type still finds the adapters and FBs it uses;
--fb-semantics M: the IEC 61499 execution model of every run)

Mutations: delete, duplicate or replace a random span; insert random bytes
(including NUL and non-ASCII) or a keyword of the input languages;
truncate. Deterministic for a given seed.
Prints one summary line; exits 1 on the first failure, printing the input.
"""
import random
import re
import subprocess
import sys
import tempfile
import os


# Words that make mutations reach past the lexer into parsers and checkers.
WORDS = [b" attr ", b" \"", b"\\", b" = \"x\";", b" IF ", b" THEN ", b" END_IF;", b" ELSE ", b" := ", b" VAR ", b" END_VAR ",
         b" FOR i := 1 TO 3 DO ", b" END_FOR;", b" CASE x OF ", b" END_CASE;",
         b" TON", b" T#1s", b" T#0s", b"(IN := TRUE, PT := T#5s);", b" RETURN;",
         b" EXIT;", b" WHILE ", b" DO ", b" INT", b" BOOL", b" ARRAY[1..2] OF ",
         b"\n  LD ", b"\n  ST ", b"\n  JMPC l\n", b"\nl:\n", b" AND( ", b"\n)\n",
         b" CAL ", b" %IX0.1 ", b" 16#FF ", b" -32768 ", b" trans ", b" place ",
         b" module ", b" @1:2:3", b"\nsource 2 = \"x.st\";\n", b"{range 0..3}", b" FUNCTION_BLOCK ", b" END_PROGRAM ",
         b" -> ", b' [label="a/b"]', b" digraph ", b"<br/>", b" subgraph { ",
         b"\n.i 2\n", b"\n# symbol input 0 = a\n",
         # PLCopen XML: wiring and element attributes.
         b' refLocalId="2"', b'<connection refLocalId="1"/>',
         b' formalParameter="OUT"', b' negated="true"', b' edge="rising"',
         b' storage="reset"', b' executionOrderId="1"', b' localId="3"',
         b'<jump localId="77" label="x"/>', b'<label localId="78" label="x"/>',
         b'<continuation localId="79" name="c"/>', b' instanceName="t"',
         # IEC 61499: interfaces, ECCs, networks.
         b'<With Var="X"/>', b'<Event Name="REQ"/>', b'<ECState Name="S"/>',
         b'<ECAction Algorithm="OUT" Output="CNF"/>', b' Condition="REQ[x]"',
         b'<ECTransition Source="START" Destination="S" Condition="1"/>',
         b'<Parameter Name="DT" Value="T#1s"/>', b'<FB Name="e" Type="E_SPLIT"/>',
         b'<Connection Source="a.EO" Destination="b.EI"/>', b' ArraySize="2"',
         b' Type="INT"', b'<Algorithm Name="A"><ST Text="x := 1;"/></Algorithm>']

# Automata are read by `mealy` and `edit-automaton`, models by the rest.
AUTOMATA = (".kiss2", ".dot")


def mutate(rng, data):
    if not data:
        return bytes(rng.randrange(256) for _ in range(rng.randrange(1, 16)))
    kind = rng.randrange(6)
    if kind == 5:
        i = rng.randrange(len(data) + 1)
        return data[:i] + rng.choice(WORDS) + data[i:]
    i = rng.randrange(len(data))
    j = min(len(data), i + rng.randrange(1, 40))
    if kind == 0:
        return data[:i] + data[j:]
    if kind == 1:
        return data[:j] + data[i:j] + data[j:]
    if kind == 2:
        return data[:i] + bytes(rng.choice(b"{}()[];:,.-><=*&|#'0123456789 \n\x00\xff")
                                for _ in range(j - i)) + data[j:]
    if kind == 3:
        return data[:i] + bytes(rng.randrange(256) for _ in range(rng.randrange(1, 8))) + data[i:]
    return data[:i]


def main():
    netlift, seed, count = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    files, include = sys.argv[4:], []
    while files[:1] in (["-I"], ["--fb-semantics"]):
        include, files = include + files[:2], files[2:]
    corpus = [(os.path.splitext(f)[1] or ".net", open(f, "rb").read())
              for f in files]
    rng = random.Random(seed)
    codes = {0: 0, 1: 0}
    with tempfile.TemporaryDirectory() as tmp:
        for n in range(count):
            ext, data = rng.choice(corpus)
            path = os.path.join(tmp, "m" + ext)
            for _ in range(rng.randrange(1, 4)):
                data = mutate(rng, data)
            with open(path, "wb") as f:
                f.write(data)
            if ext in AUTOMATA:
                commands = [["mealy", path], ["mealy", path, "--minimize", "--to", "dot"],
                            ["edit-automaton", path]]
            elif ext in (".json", ".csv"):
                # State files (sr) and built edit automata (edit-automaton).
                commands = [["sr", path, "--attr", "x=1 == 1"],
                            ["edit-automaton", path, "--from", "json"]]
            else:
                commands = [["translate", path, *include],
                            ["opt", path, "-p", "flatten"],
                            ["reach", path, "-q", "--max-states", "2000",
                             "--time-limit", "5", *include],
                            ["emit", path, "--to", "smv", *include]]
            for args in commands:
                try:
                    r = subprocess.run([netlift] + args, capture_output=True, timeout=20)
                except subprocess.TimeoutExpired:
                    print(f"mutation {n}: hang on {args}\n{data!r}")
                    return 1
                # reach may also stop at its limits (2) or find nothing (3).
                ok_codes = (0, 1, 2, 3) if args[0] == "reach" else (0, 1)
                # UBSan writes `File.cpp:12:3: runtime error: ...`; the
                # input's own text may contain the words.
                bad = r.returncode not in ok_codes or b"Sanitizer" in r.stderr \
                    or re.search(rb"\.(cpp|h):\d+:\d+: runtime error", r.stderr) \
                    or b"Assertion" in r.stderr
                if bad:
                    print(f"mutation {n}: exit {r.returncode} on {args}\n{data!r}\n"
                          f"{r.stderr.decode(errors='replace')[-2000:]}")
                    return 1
                codes[min(r.returncode, 1)] += 1
    print(f"mutations: {count}, runs exiting 0: {codes[0]}, exiting 1: {codes[1]}, crashes: 0")
    return 0


if __name__ == "__main__":
    sys.exit(main())
