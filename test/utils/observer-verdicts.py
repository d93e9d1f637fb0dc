#!/usr/bin/env python3
"""The cross-check of issue 70: every `netlift check --ctl` command of the
suite's tests is run twice, as written and with --keep-all (no end-of-scan
resets: every function-block member keeps the value the PLC gives it), and
the verdicts of every property must agree. Prints one line per difference
and a summary with the counts.

usage: observer-verdicts.py NETLIFT SRCROOT WORKDIR
"""
import concurrent.futures
import os
import re
import shlex
import subprocess
import sys



def first_command(run):
    """The command before the first pipe or redirection outside quotes."""
    quote = None
    for i, c in enumerate(run):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "|>" or run.startswith("2>", i):
            return run[:i].strip()
    return run.strip()


netlift, srcroot, work = sys.argv[1:4]
tests = os.path.join(srcroot, "test")
# "fails with abstract timers" is a verdict too (kept members can make the
# timers exact, and the verdict is then said without it).
verdict = re.compile(r"^(.*): (holds|fails)(?: with abstract timers)?$", re.M)
jobs = []  # (test path, RUN line, argv)
skipped = 0
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
            cmd = first_command(run)
            for prefix in ("not ", "%show-exit "):
                if cmd.startswith(prefix):
                    cmd = cmd[len(prefix):]
            cmd = (cmd.replace("%netlift", netlift)
                   .replace("%examples", os.path.join(srcroot, "examples"))
                   .replace("%srcroot", srcroot)
                   .replace("%S", os.path.dirname(path))
                   .replace("%s", path).replace("%t", tmp))
            if "%" in cmd or "--trace-dir" in cmd or "--keep" in cmd:
                skipped += 1
                continue
            jobs.append((path, run, shlex.split(cmd)))


def verdicts(job):
    args = job[2]
    base = subprocess.run(args, capture_output=True, text=True)
    kept = subprocess.run(args + ["--keep-all"], capture_output=True,
                          text=True)
    # The last verdict per property (--timers=abstract says a refuted
    # abstract one before refining).
    return (list(dict(verdict.findall(base.stdout)).items()),
            list(dict(verdict.findall(kept.stdout)).items()))


commands = properties = differ = 0
with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 2) as pool:
    results = list(pool.map(verdicts, jobs))
for (path, run, _), (a, b) in zip(jobs, results):
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
