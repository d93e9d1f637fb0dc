#!/usr/bin/env python3
"""Instantiates every FB type of an IEC 61499 type library in a system, as a
4diac user places a library block: one block in an application, mapped to a
resource that holds its copy (4diac writes both), and translates each system
with the library on -I. Prints how many translate and, per reason (names and
numbers elided), how many are refused; any other exit is a crash. A block
alone has nothing connected, so generic functions keep only their events.

usage: iec61499-library-systems.py NETLIFT LIBRARY_DIR
"""
import os
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


def main():
    netlift, library = sys.argv[1], sys.argv[2]
    if not os.path.isdir(library):
        print(f"library not found at {library}: nothing instantiated")
        return 0
    types = sorted(f[:-4] for _, _, fs in os.walk(library) for f in fs
                   if f.endswith(".fbt"))
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
