import os, subprocess, sys, tempfile
netlift, root = sys.argv[1], sys.argv[2]
passed = failed = 0
built, refused = 0, []
with tempfile.TemporaryDirectory() as tmp:
    for f in sorted(os.listdir(root)):
        if not f.endswith(".kiss2"):
            continue
        a, b = os.path.join(tmp, "a.kiss2"), os.path.join(tmp, "b.kiss2")
        r1 = subprocess.run([netlift, "mealy", os.path.join(root, f), "-o", a],
                            capture_output=True, text=True)
        r2 = subprocess.run([netlift, "mealy", a, "-o", b],
                            capture_output=True, text=True) if r1.returncode == 0 else r1
        ok = not (r1.returncode or r2.returncode) and open(a).read() == open(b).read()
        # The minimised machine must be equivalent to the original.
        mn = os.path.join(tmp, "min.kiss2")
        r3 = subprocess.run([netlift, "mealy", os.path.join(root, f), "--minimize", "-o", mn],
                            capture_output=True, text=True)
        r4 = subprocess.run([netlift, "mealy", os.path.join(root, f), "--equiv", mn],
                            capture_output=True, text=True) if r3.returncode == 0 else r3
        ok = ok and r3.returncode == 0 and r4.returncode == 0 and r4.stdout == "equivalent\n"
        # Its edit automaton builds, or is refused with a message (some
        # machines give ambiguous desynchronised observations; see
        # docs/enforce.md); never a crash.
        r5 = subprocess.run([netlift, "edit-automaton", os.path.join(root, f), "-o", os.devnull],
                            capture_output=True, text=True, timeout=300)
        ok = ok and (r5.returncode == 0 or
                     (r5.returncode == 1 and "netlift: error: " in r5.stderr))
        if r5.returncode == 0:
            built += 1
        else:
            refused.append(f[:-6])
        if not ok:
            print("FAIL", f, r1.stderr[:200], r2.stderr[:200], r3.stderr[:200], r4.stdout[:200])
            failed += 1
        else:
            states = [l.split()[1] for l in open(mn) if l.startswith(".s ")][0]
            print(f"ok {f}: minimal {states} states")
            passed += 1
print(f"{passed} passed, {failed} failed")
print(f"edit automata: {built} built, {len(refused)} refused ({' '.join(refused)})")
