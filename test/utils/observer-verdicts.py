#!/usr/bin/env python3
"""The cross-check of issue 70: every `netlift check --ctl` command of the
suite's tests is run twice, as written and with --keep-all (no end-of-scan
resets: every function-block member keeps the value the PLC gives it), and
the verdicts of every property must agree. Prints one line per difference
and a summary with the counts.

usage: observer-verdicts.py NETLIFT SRCROOT WORKDIR
"""
import os
import re
import shlex
import subprocess
import sys

netlift, srcroot, work = sys.argv[1:4]
tests = os.path.join(srcroot, "test")
verdict = re.compile(r"^(.*): (holds|fails)$", re.M)
commands = properties = differ = skipped = 0
for root, _, files in sorted(os.walk(tests)):
    for name in sorted(files):
        if not name.endswith(".test"):
            continue
        path = os.path.join(root, name)
        text = open(path, encoding="utf-8").read()
        runs = [l.split("RUN:", 1)[1].strip() for l in text.splitlines()
                if "RUN:" in l and "%netlift check" in l and "--ctl" in l]
        if not runs:
            continue
        tmp = os.path.join(work, os.path.relpath(path, tests)) + ".tmp"
        os.makedirs(os.path.dirname(tmp), exist_ok=True)
        if "split-file %s %t" in text:
            subprocess.run(["rm", "-rf", tmp])
            subprocess.run(["split-file", path, tmp], capture_output=True)
        for run in runs:
            cmd = run.split("|")[0].strip()
            if cmd.startswith("not "):
                cmd = cmd[4:]
            cmd = (cmd.replace("%netlift", netlift)
                   .replace("%examples", os.path.join(srcroot, "examples"))
                   .replace("%srcroot", srcroot)
                   .replace("%S", os.path.dirname(path))
                   .replace("%s", path).replace("%t", tmp))
            if "%" in cmd or "--trace-dir" in cmd:
                skipped += 1
                continue
            args = shlex.split(cmd)
            base = subprocess.run(args, capture_output=True, text=True)
            kept = subprocess.run(args + ["--keep-all"], capture_output=True,
                                  text=True)
            a = verdict.findall(base.stdout)
            b = verdict.findall(kept.stdout)
            if not a:
                skipped += 1
                continue
            commands += 1
            properties += len(a)
            if a != b:
                differ += 1
                print("differ:", os.path.relpath(path, tests), run)
                print("  with resets:", a)
                print("  --keep-all: ", b)
print(f"{commands} check commands, {properties} properties, "
      f"{differ} differ, {skipped} skipped")
