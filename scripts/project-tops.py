#!/usr/bin/env python3
"""Issue 37's measure: translates each TwinCAT/CODESYS project given (a
.plcproj, or a directory holding PLC sources) once per PROGRAM and
FUNCTION_BLOCK it declares, as `netlift translate PROJECT --top NAME`, and
prints how many translate, the refusals grouped by reason (names and
numbers elided, as corpus-sweep.py does) and any crash or hang (exit other
than 0/1, or over 120 s). Exits 1 if anything crashed.

usage: project-tops.py NETLIFT PROJECT...
"""
import collections
import os
import re
import subprocess
import sys

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


def reason(stderr):
    for line in stderr.splitlines():
        if ": error: " in line:
            msg = line.split(": error: ", 1)[1]
            return re.sub(r"\d+", "N", re.sub(r"'[^']*'", "'…'", msg))
    return "(no message)"


def main():
    netlift, projects = sys.argv[1], sys.argv[2:]
    ok, total, refused, crashed = 0, 0, collections.Counter(), []
    for project in projects:
        for name in pous(project):
            total += 1
            try:
                r = subprocess.run([netlift, "translate", project, "--top",
                                    name, "-o", os.devnull],
                                   capture_output=True, text=True,
                                   timeout=120)
            except subprocess.TimeoutExpired:
                crashed.append(f"{project} --top {name}: hang")
                continue
            if r.returncode == 0:
                ok += 1
            elif r.returncode == 1:
                refused[reason(r.stderr)] += 1
            else:
                crashed.append(f"{project} --top {name}: exit {r.returncode}")
    print(f"tops: {total} PROGRAMs and FBs, {ok} translated, "
          f"{sum(refused.values())} refused, {len(crashed)} crashed")
    for why, n in refused.most_common():
        print(f"  {n:5}  {why}")
    for c in crashed:
        print(f"  CRASH {c}")
    return 1 if crashed else 0


if __name__ == "__main__":
    sys.exit(main())
