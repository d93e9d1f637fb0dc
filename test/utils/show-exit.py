#!/usr/bin/env python3
"""Runs a command and prints `exit N`, then its stdout, then its stderr, so
a lit test can check an exit code other than 0/1 (lit's `not` only inverts)."""
import subprocess
import sys

r = subprocess.run(sys.argv[1:], capture_output=True, text=True)
print("exit", r.returncode)
sys.stdout.write(r.stdout)
sys.stdout.write(r.stderr)
