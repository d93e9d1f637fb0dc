#!/usr/bin/env python3
"""Instantiates every FB type of an IEC 61499 type library in a system, as a
4diac user places a library block: one block in an application, mapped to a
resource that holds its copy (4diac writes both), and translates each system
with the library on -I. Prints how many translate and, per reason (names and
numbers elided), how many are refused; any other exit is a crash. A block
alone has nothing connected, so generic functions keep only their events.

usage: iec61499-library-systems.py NETLIFT LIBRARY_DIR
"""
import collections
import os
import re
import subprocess
import sys
import tempfile

SYSTEM = """<?xml version="1.0" encoding="UTF-8"?>
<System Name="S_{name}">
  <Application Name="App">
    <SubAppNetwork>
      <FB Name="b" Type="{name}" x="100" y="100"/>
    </SubAppNetwork>
  </Application>
  <Device Name="PLC" Type="FORTE_PC" x="0" y="0">
    <Parameter Name="MGR_ID" Value="&quot;localhost:61499&quot;"/>
    <Resource Name="RES" Type="EMB_RES" x="0" y="0">
      <FBNetwork>
        <FB Name="b" Type="{name}" x="100" y="100"/>
      </FBNetwork>
    </Resource>
  </Device>
  <Mapping From="App.b" To="PLC.RES.b"/>
</System>
"""


def reason(stderr):
    for line in stderr.splitlines():
        if ": error: " in line:
            msg = line.split(": error: ", 1)[1]
            return re.sub(r"\d+", "N", re.sub(r"'[^']*'", "'…'", msg))
    return "(no message)"


def main():
    netlift, library = sys.argv[1], sys.argv[2]
    if not os.path.isdir(library):
        print(f"library not found at {library}: nothing instantiated")
        return 0
    types = sorted(f[:-4] for _, _, fs in os.walk(library) for f in fs
                   if f.endswith(".fbt"))
    ok, refused, crashed = 0, collections.Counter(), []
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "one.sys")
        for name in types:
            with open(path, "w") as f:
                f.write(SYSTEM.format(name=name))
            try:
                r = subprocess.run([netlift, "translate", path, "-I", library,
                                    "-o", os.devnull], capture_output=True,
                                   text=True, timeout=120, errors="replace")
            except subprocess.TimeoutExpired:
                crashed.append((name, "hang"))
                continue
            if r.returncode == 0:
                ok += 1
            elif r.returncode == 1:
                refused[reason(r.stderr)] += 1
            else:
                crashed.append((name, f"exit {r.returncode}"))
    print(f"library blocks: {len(types)} types, {ok} translate in a system, "
          f"{sum(refused.values())} refused, {len(crashed)} crashed")
    for why, n in sorted(refused.items(), key=lambda kv: (-kv[1], kv[0])):
        print(f"  {n:5}  {why}")
    for name, how in crashed:
        print(f"  CRASH {how}: {name}")
    return 1 if crashed else 0


if __name__ == "__main__":
    sys.exit(main())
