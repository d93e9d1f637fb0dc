#!/usr/bin/env python3
"""Rewrites the pinned counts of the corpus-sweep tests: the CHECK lines
between `# BEGIN PINS` and `# END PINS` of each test below become the exact
output of its sweep script (scripts/corpus-sweep.py for its formats: files,
translated, refused per reason, crashed; scripts/sfc-sweep.py: each SFC
file's outcome), so a change that moves a count fails its test
until the pins are updated in the same commit, which says why.

usage: update-sweep-pins.py NETLIFT [CORPUS_DIR]
"""
import os
import re
import subprocess
import sys

# Test file (relative to the source root) -> the sweep script and the
# formats it sweeps.
TESTS = {
    "test/frontends/pnml/corpus-sweep.test": ("corpus-sweep.py", ["pnml"]),
    "test/frontends/st/corpus-sweep.test": ("corpus-sweep.py", ["st"]),
    "test/frontends/il/corpus-sweep.test": ("corpus-sweep.py", ["il"]),
    "test/frontends/tcpou/corpus-sweep.test": ("corpus-sweep.py", ["tcpou"]),
    "test/frontends/plcopen/corpus-sweep.test":
        ("corpus-sweep.py", ["plcopen_xml"]),
    "test/frontends/iec61499/corpus-sweep.test":
        ("corpus-sweep.py", ["iec61499"]),
    "test/frontends/iec61499/corpus-sweep-libraries.test":
        ("corpus-sweep.py", ["iec61499-libraries"]),
    "test/frontends/hybrid/corpus-sweep.test": ("corpus-sweep.py", ["spaceex"]),
    "test/passes/discretise/corpus-sweep.test":
        ("corpus-sweep.py", ["spaceex-discretise"]),
    "test/frontends/sfc/corpus-sweep.test": ("sfc-sweep.py", []),
}


def escape(line):
    # FileCheck reads {{...}} and [[...]] as patterns.
    return line.replace("{{", "{{[{][{]}}").replace("[[", "{{[[][[]}}")


def main():
    if len(sys.argv) < 2 or sys.argv[1].startswith("-") or not os.access(
            sys.argv[1], os.X_OK):
        sys.exit(__doc__.strip().split("\n\n")[-1])
    netlift = os.path.abspath(sys.argv[1])
    root = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))
    corpus = sys.argv[2] if len(sys.argv) > 2 else os.path.join(
        root, "..", "shared", "corpus")
    if not os.path.isdir(corpus):
        sys.exit(f"update-sweep-pins: no corpus at {corpus}")
    for test, (script, formats) in TESTS.items():
        sweep = os.path.join(root, "scripts", script)
        run = subprocess.run([sys.executable, sweep, netlift, corpus] +
                             formats, capture_output=True, text=True)
        lines = run.stdout.rstrip("\n").split("\n")
        # A sweep that failed or printed no summary (a wrong NETLIFT, a
        # missing corpus) must not become the pins.
        if (run.returncode != 0 or not run.stdout.strip() or
                re.match(r"\S+: 0 files", lines[0])):
            sys.exit(f"update-sweep-pins: {test}: the sweep failed, pins "
                     f"kept "
                     f"(exit {run.returncode}): {run.stderr.strip()[-500:]}")
        pins = ["# CHECK: " + escape(lines[0].strip())]
        pins += ["# CHECK-NEXT: " + escape(l.strip()) for l in lines[1:]]
        pins.append("# CHECK-NOT: {{.}}")
        path = os.path.join(root, test)
        text = open(path).read()
        new = re.sub(r"(# BEGIN PINS[^\n]*\n).*?(# END PINS)",
                     lambda m: m.group(1) + "\n".join(pins) + "\n" +
                     m.group(2), text, flags=re.S)
        if new != text:
            open(path, "w").write(new)
            print(f"updated {test}")


if __name__ == "__main__":
    main()
