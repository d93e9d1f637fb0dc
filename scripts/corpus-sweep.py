#!/usr/bin/env python3
"""Runs `netlift translate` (`netlift mealy` for automata) over every file of ../shared/corpus that a
frontend exists for and prints, per format, how many files were translated,
refused (grouped by reason, names and numbers elided, most frequent first)
and crashed (any exit other than 0/1, or a hang), and every refusal whose
error does not say where (file:line:col: UNLOCATED). Exits 1 if anything
crashed or a refusal is unlocated.

usage: corpus-sweep.py NETLIFT [CORPUS_DIR [FORMAT...]]
"""
import collections
import os
import re
import subprocess
import sys

from sweep_reasons import reason

# Format -> (file extensions, --from format or None for "by extension",
# files to skip, subcommand and its options[, the corpus folder when it is
# not the format's name]). matiec keeps ST in .txt and .test files.
FORMATS = {
    "pnml": ((".pnml",), None, (), "translate"),
    "st": ((".st", ".txt", ".test", ".EXP"), "st",
           ("PROVENANCE.txt", "readme"), "translate"),
    "il": ((".il", ".txt"), "il", (), "translate"),
    "tcpou": ((".TcPOU", ".TcGVL", ".TcDUT", ".TcIO", ".TcTTO"), None, (),
              "translate"),
    "kiss2": ((".kiss2",), None, (), "mealy"),
    "dot": ((".dot",), None, (), "mealy"),
    "spaceex": ((".xml",), None, (), "translate"),
    # The same files on to a discretised timed net (issue 39's measure).
    "spaceex-discretise": ((".xml",), None, (),
                           "opt -p discretise{grid=4}", "spaceex"),
    "plcopen_xml": ((".xml",), None, (), "translate"),
    "iec61499": ((".fbt", ".sub", ".sys", ".adp", ".dtp", ".fct", ".dev",
                  ".res", ".seg", ".atp", ".gcf"), None, (), "translate"),
    # The same files with their project's types on -I, as a 4diac user
    # translates them (issue 38's measure).
    "iec61499-libraries": ((".fbt", ".sub", ".sys", ".adp", ".dtp", ".fct",
                            ".dev", ".res", ".seg", ".atp", ".gcf"), None,
                           (), "translate", "iec61499"),
}

# Formats whose files are translated with `-I <their project>`: the folder
# of the corpus format's directory that holds them (4diac-ide, fb2smv).
WITH_PROJECT_LIBRARIES = {"iec61499-libraries"}


LOCATED = re.compile(r"^.+:\d+:\d+: error: ")


def located(stderr):
    """Does the first error say where (file:line:col)?"""
    for line in stderr.splitlines():
        if ": error: " in line:
            return bool(LOCATED.match(line))
    return False


def main():
    netlift = sys.argv[1]
    here = os.path.dirname(os.path.abspath(__file__))
    corpus = sys.argv[2] if len(sys.argv) > 2 else os.path.join(
        here, "..", "..", "shared", "corpus")
    if not os.path.isdir(corpus):
        print(f"corpus not found at {corpus}: nothing swept")
        return 0
    crashed_any = False
    only = sys.argv[3:]
    for fmt, (exts, from_fmt, skip, command, *folder) in FORMATS.items():
        if only and fmt not in only:
            continue
        files = sorted(os.path.join(d, f)
                       for d, _, fs in os.walk(
                           os.path.join(corpus, folder[0] if folder else fmt))
                       for f in fs if f.endswith(exts) and f not in skip)
        ok, refused, crashed, unlocated = 0, collections.Counter(), [], []
        for f in files:
            try:
                cmd = [netlift, *command.split(), f, "-o", os.devnull]
                if fmt in WITH_PROJECT_LIBRARIES:
                    top = os.path.join(corpus, folder[0] if folder else fmt)
                    project = os.path.relpath(f, top).split(os.sep)[0]
                    cmd += ["-I", os.path.join(top, project)]
                if from_fmt:
                    cmd += ["--from", from_fmt]
                r = subprocess.run(cmd, capture_output=True, text=True,
                                   timeout=120, errors="replace")
            except subprocess.TimeoutExpired:
                crashed.append((f, "hang"))
                continue
            if r.returncode == 0:
                ok += 1
            elif r.returncode == 1:
                refused[reason(r.stderr)] += 1
                if not located(r.stderr):
                    unlocated.append((f, reason(r.stderr)))
            else:
                crashed.append((f, f"exit {r.returncode}"))
            if os.environ.get("SWEEP_VERBOSE") and r.returncode != 0:
                print(f"    {f}: {reason(r.stderr)}")
        print(f"{fmt}: {len(files)} files, {ok} translated, "
              f"{sum(refused.values())} refused, {len(crashed)} crashed")
        # Most frequent first, ties by the reason's text: stable pins.
        for why, n in sorted(refused.items(), key=lambda kv: (-kv[1], kv[0])):
            print(f"  {n:5}  {why}")
        for f, how in crashed:
            print(f"  CRASH {how}: {f}")
        # A refusal must say where: file:line:col.
        for f, why in unlocated:
            print(f"  UNLOCATED {os.path.relpath(f, corpus)}: {why}")
        crashed_any |= bool(crashed) or bool(unlocated)
    return 1 if crashed_any else 0


if __name__ == "__main__":
    sys.exit(main())
