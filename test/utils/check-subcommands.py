#!/usr/bin/env python3
"""Diffs every list of netlift's subcommands against the subcommand table
(tools/netlift/SubcommandRegistry.def): the overview and the SUBCOMMANDS
section of `netlift --help`, the overview's list of exploring commands,
the message of `netlift` with no subcommand, the man pages and the bash
completion made from the binary (scripts/make-cli-files.py).

usage: check-subcommands.py NETLIFT SRCROOT BUILDDIR
Prints one line per list that agrees, `MISMATCH ...` for one that does
not (exit 1).
"""
import os
import re
import subprocess
import sys


def run(*args):
    r = subprocess.run(list(args), capture_output=True, text=True)
    return r.stdout + r.stderr


def table(srcroot):
    text = open(os.path.join(srcroot, "tools/netlift/SubcommandRegistry.def")).read()
    rows = re.findall(r'NETLIFT_SUBCOMMAND\(\s*\w+,\s*"([\w-]+)",.*?'
                      r'(true|false),\s*(true|false),\s*\w+\)', text, re.S)
    return [(name, explores == "true") for name, _, explores in rows]


def main():
    netlift, srcroot, builddir = sys.argv[1:4]
    rows = table(srcroot)
    names = [n for n, _ in rows]
    exploring = [n for n, e in rows if e]
    top = run(netlift, "--help")
    lists = {
        "overview": re.findall(r"^  netlift ([\w-]+) ", top, re.M),
        "--help SUBCOMMANDS": sorted(
            re.findall(r"^  ([\w-]+)\s+- ", top.split("SUBCOMMANDS:")[1]
                       .split("OPTIONS:")[0], re.M)),
        "exploring commands": re.search(r"Exploring commands \(([^)]*)\)",
                                        top).group(1).split(", "),
        "no subcommand": re.search(r"no subcommand given \(([^)]*)\)",
                                   run(netlift)).group(1).split(", "),
        "man pages": sorted(
            f[len("netlift-"):-2]
            for f in os.listdir(os.path.join(builddir, "cli/man/man1"))
            if f.startswith("netlift-")),
        "completion": re.search(r'compgen -W "([^"]*)"',
                                open(os.path.join(builddir,
                                                  "cli/completion/netlift"))
                                .read()).group(1).split(),
    }
    expected = {"overview": names, "--help SUBCOMMANDS": sorted(names),
                "exploring commands": exploring,
                "no subcommand": names, "man pages": sorted(names),
                "completion": None}
    bad = 0
    for what, got in lists.items():
        want = expected[what]
        if want is None:  # the completion's order is its own
            got, want = sorted(got), sorted(names)
        if got == want:
            print(f"{what}: {len(got)} subcommands, as the table")
        else:
            bad += 1
            print(f"MISMATCH {what}: {got} != table {want}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
