#!/usr/bin/env python3
"""Instantiates every FB type of an IEC 61499 type library in a system, as a
4diac user places a library block: one block in an application, mapped to a
resource that holds its copy (4diac writes both), and translates each system
with the library on -I. Prints how many translate and, per reason (names and
numbers elided), how many are refused; any other exit is a crash. A block
alone has nothing connected, so generic functions keep only their events.

With --by-name, each system is translated twice, with the library on -I
and without it, where netlift takes the types of 4diac's standard library
by name (frontends/iec61499/Iec61499Standard.cpp): prints how many types
netlift knows by name, how many of those give the same NetIR as 4diac's own
file (source lines and locations aside), and names the others (where
netlift's model replaces 4diac's service FB or composite).

usage: iec61499-library-systems.py [--by-name] NETLIFT LIBRARY_DIR
"""
import os
import re
import subprocess
import sys

from sweep_reasons import Tally
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


def without_sources(net):
    """NetIR without what says where it came from."""
    net = re.sub(r"(?m)^source .*\n", "", net)
    return re.sub(r" @[0-9:]+", "", net)


def compare_by_name(netlift, library, types):
    known, same, differ = 0, 0, []
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "one.sys")
        for name in types:
            with open(path, "w") as f:
                f.write(SYSTEM.format(name=name))
            alone = subprocess.run([netlift, "translate", path],
                                   capture_output=True, text=True)
            if alone.returncode != 0:
                continue
            known += 1
            with_lib = subprocess.run(
                [netlift, "translate", path, "-I", library],
                capture_output=True, text=True)
            if without_sources(with_lib.stdout) == without_sources(
                    alone.stdout):
                same += 1
            else:
                differ.append(name)
    print(f"by name: {len(types)} types, {known} known without the library, "
          f"{same} the same as 4diac's file")
    print("netlift's own model: " + " ".join(differ))
    return 0


def main():
    by_name = "--by-name" in sys.argv
    args = [a for a in sys.argv[1:] if a != "--by-name"]
    netlift, library = args[0], args[1]
    if not os.path.isdir(library):
        print(f"library not found at {library}: nothing instantiated")
        return 0
    types = sorted(f[:-4] for _, _, fs in os.walk(library) for f in fs
                   if f.endswith(".fbt"))
    if by_name:
        return compare_by_name(netlift, library, types)
    tally = Tally()
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "one.sys")
        for name in types:
            with open(path, "w") as f:
                f.write(SYSTEM.format(name=name))
            tally.run([netlift, "translate", path, "-I", library, "-o",
                       os.devnull], name)
    return tally.report(f"library blocks: {len(types)} types, "
                        f"{tally.translated} translate in a system")


if __name__ == "__main__":
    sys.exit(main())
