import os, subprocess, sys, tempfile
netlift, root = sys.argv[1], sys.argv[2]
passed = failed = 0
with tempfile.TemporaryDirectory() as tmp:
    for f in sorted(os.listdir(root)):
        if not f.endswith(".kiss2"):
            continue
        a, b = os.path.join(tmp, "a.kiss2"), os.path.join(tmp, "b.kiss2")
        r1 = subprocess.run([netlift, "mealy", os.path.join(root, f), "-o", a],
                            capture_output=True, text=True)
        r2 = subprocess.run([netlift, "mealy", a, "-o", b],
                            capture_output=True, text=True) if r1.returncode == 0 else r1
        if r1.returncode or r2.returncode or open(a).read() != open(b).read():
            print("FAIL", f, r1.stderr[:200], r2.stderr[:200])
            failed += 1
        else:
            passed += 1
print(f"{passed} passed, {failed} failed")
