#!/usr/bin/env python3
"""Translates every SFC source of ../shared/corpus (textual SFC in ST files,
<SFC> bodies in PLCopen XML) and prints, per file, `translated` or the
first error with names and numbers elided. A file that declares no PROGRAM
is translated with --top on its first function block written in SFC.
Exits 1 on a crash or an unlocated error.

usage: sfc-sweep.py NETLIFT CORPUS_DIR
"""
import os
import re
import subprocess
import sys


def main():
    netlift, corpus = sys.argv[1], sys.argv[2]
    found = []
    for folder in ("st", "plcopen_xml"):
        for root, dirs, files in os.walk(os.path.join(corpus, folder)):
            dirs.sort()
            for f in sorted(files):
                path = os.path.join(root, f)
                try:
                    text = open(path, encoding="utf-8", errors="replace").read()
                except OSError:
                    continue
                if re.search(r"^\s*INITIAL_STEP\b", text, re.M) or "<SFC>" in text:
                    found.append((folder, path, text))
    bad = 0
    for folder, path, text in found:
        args = [netlift, "translate", path, "-o", os.devnull]
        if folder == "st":
            args += ["--from", "st"]
            if not re.search(r"^\s*PROGRAM\s+\w+", text, re.M | re.I):
                fbs = re.findall(r"FUNCTION_BLOCK\s+(\w+)((?:(?!END_FUNCTION_BLOCK).)*)",
                                 text, re.S | re.I)
                sfc = [n for n, body in fbs if "INITIAL_STEP" in body]
                if sfc:
                    args += ["--top", sfc[0]]
        try:
            r = subprocess.run(args, capture_output=True, text=True, timeout=60)
        except subprocess.TimeoutExpired:
            print(f"{os.path.relpath(path, corpus)}: HANG")
            bad = 1
            continue
        rel = os.path.relpath(path, corpus)
        if r.returncode == 0:
            print(f"{rel}: translated")
            continue
        if r.returncode != 1:
            print(f"{rel}: CRASH (exit {r.returncode})")
            bad = 1
            continue
        err = next((l for l in r.stderr.splitlines() if ": error: " in l), "")
        if not re.match(r"^.+:\d+:\d+: error: ", err):
            print(f"{rel}: UNLOCATED {err}")
            bad = 1
            continue
        msg = re.sub(r"'[^']*'", "'…'", err.split(": error: ", 1)[1])
        print(f"{rel}: {msg}")
    print(f"{len(found)} SFC files")
    return bad


if __name__ == "__main__":
    sys.exit(main())
