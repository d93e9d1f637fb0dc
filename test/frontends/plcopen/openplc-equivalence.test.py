"""For each Ladder tutorial of OpenPLC (PLCopen XML) and the ST that OpenPLC
generated from the same ladder, makes the variables the program only reads
inputs (%IX) and those it writes outputs (%QX) in both, then requires the
same minimal Mealy machine (netlift mealy --minimize --equiv) and the same
reachable state and edge counts. Prints one line per tutorial.

usage: openplc-equivalence.test.py NETLIFT CORPUS TMPDIR
"""
import json
import os
import re
import subprocess
import sys

netlift, corpus, tmp = sys.argv[1:4]
xml_root = os.path.join(corpus, "plcopen_xml", "OpenPLC_Tutorials")
st_root = os.path.join(corpus, "st", "OpenPLC_Tutorials")
os.makedirs(tmp, exist_ok=True)


def run(*args):
    return subprocess.run([netlift, *args], capture_output=True, text=True)


def summary(path):
    r = run("reach", path, "--summary", "json", "-q")
    d = json.loads(r.stdout)
    return d["states"], d["transitions"]


for d, _, files in sorted(os.walk(xml_root)):
    if "plc.xml" not in files:
        continue
    rel = os.path.relpath(d, xml_root)
    st_path = os.path.join(st_root, rel, "build", "generated_plc.st")
    if not os.path.exists(st_path):
        continue
    xml = open(os.path.join(d, "plc.xml"), encoding="utf-8").read()
    st = open(st_path, encoding="utf-8").read()
    body = st.split("END_VAR", 1)[1]
    written = set(re.findall(r"(\w+)\s*:=", body))
    names = re.findall(r'<variable name="(\w+)">', xml)
    inputs = [n for n in names if n not in written]
    outputs = [n for n in names if n in written]
    # plc.st is what OpenPLC compiles: the same program after its LOGGER
    # block, written in C, which the program does not call.
    compiled_path = os.path.join(st_root, rel, "build", "plc.st")
    compiled = open(compiled_path, encoding="utf-8").read() \
        if os.path.exists(compiled_path) else None

    def locate(text, n, address):
        return re.sub(rf"\b{n}\s*:\s*BOOL", f"{n} AT {address} : BOOL", text)

    for k, n in enumerate(inputs):
        xml = xml.replace(f'<variable name="{n}">',
                          f'<variable name="{n}" address="%IX0.{k}">')
        st = locate(st, n, f"%IX0.{k}")
        compiled = compiled and locate(compiled, n, f"%IX0.{k}")
    for k, n in enumerate(outputs):
        xml = xml.replace(f'<variable name="{n}">',
                          f'<variable name="{n}" address="%QX0.{k}">')
        st = locate(st, n, f"%QX0.{k}")
        compiled = compiled and locate(compiled, n, f"%QX0.{k}")
    name = re.sub(r"\W+", "_", rel.split(os.sep)[1]).strip("_")
    x_path = os.path.join(tmp, name + ".xml")
    s_path = os.path.join(tmp, name + ".st")
    open(x_path, "w", encoding="utf-8").write(xml)
    open(s_path, "w", encoding="utf-8").write(st)
    eq = run("mealy", x_path, "--minimize", "--equiv", s_path)
    verdict = eq.stdout.strip().splitlines()[0] if eq.stdout.strip() else \
        eq.stderr.strip()
    print(f"{name}: {len(inputs)} inputs, {len(outputs)} outputs, "
          f"mealy {verdict}, states/edges {summary(x_path)} vs "
          f"{summary(s_path)}")
    if compiled:
        c_path = os.path.join(tmp, name + "-compiled.st")
        open(c_path, "w", encoding="utf-8").write(compiled)
        eq = run("mealy", x_path, "--minimize", "--equiv", c_path)
        verdict = eq.stdout.strip().splitlines()[0] if eq.stdout.strip() \
            else eq.stderr.strip()
        print(f"{name} against the compiled plc.st: mealy {verdict}")
    # A control: one contact negated the other way must be told apart.
    flipped = re.sub(r'(<contact [^>]*negated=")(true|false)"',
                     lambda m: m.group(1) +
                     ("false" if m.group(2) == "true" else "true") + '"',
                     xml, count=1)
    f_path = os.path.join(tmp, name + "-flipped.xml")
    open(f_path, "w", encoding="utf-8").write(flipped)
    eq = run("mealy", f_path, "--minimize", "--equiv", s_path)
    print(f"{name} with one contact flipped: exit {eq.returncode}, "
          f"{eq.stdout.strip().splitlines()[0]}")
