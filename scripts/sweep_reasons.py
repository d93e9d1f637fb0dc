"""How the sweeps (corpus-sweep.py, project-tops.py,
iec61499-library-systems.py) group refusals: by the first error's message,
names and numbers elided, so that counts per reason can be pinned."""
import re


def reason(stderr):
    for line in stderr.splitlines():
        if ": error: " in line:
            msg = line.split(": error: ", 1)[1]
            msg = re.sub(r"'[^']*'", "'…'", msg)
            return re.sub(r"\d+", "N", msg)
    return stderr.strip().splitlines()[0] if stderr.strip() else "(no message)"


def run(cmd, timeout=120):
    """Runs one translation: ("translated", ""), ("refused", reason) for
    exit 1, or ("crashed", "hang" / "exit N") for anything else."""
    import subprocess
    try:
        r = subprocess.run(cmd, capture_output=True, text=True,
                           timeout=timeout, errors="replace")
    except subprocess.TimeoutExpired:
        return "crashed", "hang"
    if r.returncode == 0:
        return "translated", ""
    if r.returncode == 1:
        return "refused", reason(r.stderr)
    return "crashed", f"exit {r.returncode}"


def print_reasons(refused):
    """The refusals, most frequent first, ties by text: stable pins."""
    for why, n in sorted(refused.items(), key=lambda kv: (-kv[1], kv[0])):
        print(f"  {n:5}  {why}")


class Tally:
    """Counts translations run one by one: translated, refused per reason,
    crashed (with what was run)."""

    def __init__(self):
        import collections
        self.translated = 0
        self.refused = collections.Counter()
        self.crashed = []

    def run(self, cmd, label):
        outcome, why = run(cmd)
        if outcome == "translated":
            self.translated += 1
        elif outcome == "refused":
            self.refused[why] += 1
        else:
            self.crashed.append(f"{label}: {why}")

    def report(self, head):
        """Prints `head, N refused, N crashed`, the reasons and the crashes;
        returns the exit status (1 if anything crashed)."""
        print(f"{head}, {sum(self.refused.values())} refused, "
              f"{len(self.crashed)} crashed")
        print_reasons(self.refused)
        for c in self.crashed:
            print(f"  CRASH {c}")
        return 1 if self.crashed else 0
