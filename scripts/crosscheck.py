"""What the cross-check scripts (check-spin.py, check-smv.py) share: their
command line, netlift's own figures for a model, and the ok/FAIL report."""
import json
import subprocess


def split_ctl(args):
    """Takes every `--ctl FORMULA` out of `args`: (formulas, the rest)."""
    args, ctl = list(args), []
    while "--ctl" in args:
        i = args.index("--ctl")
        ctl.append(args[i + 1])
        del args[i:i + 2]
    return ctl, args


def netlift_summary(netlift, model):
    """`netlift reach --summary json` of the model, or None when a runtime
    error of the model (write conflict, range...) stops netlift."""
    r = subprocess.run([netlift, "reach", model, "--summary", "json", "-q"],
                       capture_output=True, text=True)
    if r.returncode == 1 and "runtime error" in r.stderr:
        return None
    return json.loads(r.stdout)


class Tally:
    """One `ok`/`FAIL` line per check and the closing count."""

    def __init__(self):
        self.passed = self.failed = 0

    def report(self, ok, line):
        print(("ok   " if ok else "FAIL ") + line)
        self.passed += bool(ok)
        self.failed += not ok

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        return 1 if self.failed else 0
