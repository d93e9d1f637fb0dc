#!/usr/bin/env python3
"""Issue 37's measure: translates each TwinCAT/CODESYS project given (a
.plcproj, or a directory holding PLC sources) once per PROGRAM and
FUNCTION_BLOCK it declares, as `netlift translate PROJECT --top NAME`, and
prints how many translate, the refusals grouped by reason (names and
numbers elided, as corpus-sweep.py does) and any crash or hang (exit other
than 0/1, or over 120 s). Exits 1 if anything crashed.

usage: project-tops.py NETLIFT PROJECT...
"""
import os
import re
import sys

from sweep_reasons import Tally

POU = re.compile(r"\b(?:PROGRAM|FUNCTION_BLOCK)\s+"
                 r"(?:(?:ABSTRACT|FINAL|PUBLIC|PRIVATE|PROTECTED|INTERNAL)\s+)*"
                 r"([A-Za-z_][A-Za-z0-9_]*)", re.IGNORECASE)
SOURCES = (".TcPOU", ".st")


def pous(project):
    root = project if os.path.isdir(project) else os.path.dirname(project)
    names = set()
    for d, _, files in os.walk(root):
        for f in files:
            if f.endswith(SOURCES):
                with open(os.path.join(d, f), encoding="utf-8",
                          errors="replace") as src:
                    names.update(POU.findall(src.read()))
    return sorted(names)


def main():
    netlift, projects = sys.argv[1], sys.argv[2:]
    tally, total = Tally(), 0
    for project in projects:
        for name in pous(project):
            total += 1
            tally.run([netlift, "translate", project, "--top", name, "-o",
                       os.devnull], f"{project} --top {name}")
    return tally.report(f"tops: {total} PROGRAMs and FBs, "
                        f"{tally.translated} translated")


if __name__ == "__main__":
    sys.exit(main())
