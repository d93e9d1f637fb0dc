#!/usr/bin/env bash
# Exploration of a REAL-heavy program: a PID loop with scaling and
# hysteresis whose set point is a free input (0..3, every scan), explored
# breadth-first to a fixed number of states. Prints the summary (states/s,
# bytes/state) of `netlift reach`.
# Usage: bench/real-bench.sh [BUILD_DIR] [STATES]
set -euo pipefail
build=${1:-build}
states=${2:-2000000}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/pid.st" <<'ST'
PROGRAM Pid
  VAR_INPUT
    sp : INT(0..3);
  END_VAR
  VAR
    pv : REAL := 20.0;
    err, integ, prevErr, deriv, out : REAL;
    raw : INT;
    scaled : LREAL;
    alarm : BOOL;
  END_VAR
  err := INT_TO_REAL(sp) * 10.0 - pv;
  integ := LIMIT(-100.0, integ + err * 0.1, 100.0);
  deriv := (err - prevErr) / 0.1;
  out := 0.8 * err + 0.3 * integ + 0.05 * deriv;
  prevErr := err;
  pv := pv + (out - (pv - 20.0) * 0.2) * 0.1;
  raw := REAL_TO_INT(pv * 327.67);
  scaled := INT_TO_LREAL(raw) / 327.67;
  IF scaled > 45.0 THEN
    alarm := TRUE;
  ELSIF scaled < 40.0 THEN
    alarm := FALSE;
  END_IF;
END_PROGRAM
ST
echo "== PID loop in REAL, set point free in 0..3, $states states"
"$build/bin/netlift" reach "$tmp/pid.st" --max-states "$states" \
  --summary json -o /dev/null 2>/dev/null || true
