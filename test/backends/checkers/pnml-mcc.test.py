# For each MCC model named: netlift's state-space summary of the original
# and of `emit --to pnml` of it must agree (states, edges, complete).
import json, os, subprocess, sys, tempfile
netlift, root, models = sys.argv[1], sys.argv[2], sys.argv[3:]
def summary(path):
    r = subprocess.run([netlift, "reach", path, "--summary", "json", "-q"],
                       capture_output=True, text=True, check=True)
    s = json.loads(r.stdout)
    return (s["states"], s["transitions"], s["complete"])
with tempfile.TemporaryDirectory() as tmp:
    for m in models:
        src = os.path.join(root, m, "model.pnml")
        out = os.path.join(tmp, m + ".pnml")
        subprocess.run([netlift, "emit", src, "--to", "pnml", "-o", out],
                       check=True)
        a, b = summary(src), summary(out)
        print(m, "same" if a == b else f"DIFFERENT {a} {b}")
