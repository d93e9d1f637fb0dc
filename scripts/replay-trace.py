#!/usr/bin/env python3
"""Replays a trace `netlift check --trace-dir` wrote against the state graph
`netlift reach --format json` explores for the same model: the path must
start in the initial state, every step must be an edge of the graph with
its label, and a lasso's closing step too. With `--end ATTR=VALUE...` the
last state must also have those attribute values, and with `--all
ATTR=VALUE...` every state of the path.

usage: replay-trace.py NETLIFT MODEL TRACE.json [--end A=V...] [--all A=V...]
Prints `replayed: N steps[, loop to K]` or the first mismatch; exit 1 then.
"""
import json
import subprocess
import sys


def conditions(args, flag):
    out, on = [], False
    for a in args:
        if a.startswith("--"):
            on = a == flag
        elif on:
            name, value = a.split("=", 1)
            out.append((name, int(value)))
    return out


def main():
    netlift, model, trace_file = sys.argv[1:4]
    end, every = conditions(sys.argv[4:], "--end"), conditions(sys.argv[4:],
                                                               "--all")
    r = subprocess.run([netlift, "reach", model, "--format", "json", "-q"],
                       capture_output=True, text=True, check=True)
    graph = json.loads(r.stdout)
    names = [a["name"] for a in graph["attributes"]]
    values = {s["id"]: dict(zip(names, s["values"])) for s in graph["states"]}
    edges = {(e["from"], e["label"], e["to"]) for e in graph["edges"]}
    with open(trace_file) as f:
        trace = json.load(f)
    states, labels = trace["states"], trace["labels"]

    def fail(msg):
        print("mismatch:", msg)
        sys.exit(1)

    if not states or states[0] != 0:
        fail("the path does not start in the initial state")
    for i in range(1, len(states)):
        if (states[i - 1], labels[i - 1], states[i]) not in edges:
            fail(f"step {i}: no edge {states[i - 1]} -{labels[i - 1]}->"
                 f" {states[i]}")
    loop = trace.get("loop_to")
    if loop is not None and \
            (states[-1], trace["loop_label"], states[loop]) not in edges:
        fail(f"no edge back from {states[-1]} to step {loop}")
    for name, value in end:
        if values[states[-1]][name] != value:
            fail(f"the last state has {name}={values[states[-1]][name]}")
    for name, value in every:
        for s in states:
            if values[s][name] != value:
                fail(f"state {s} has {name}={values[s][name]}")
    print(f"replayed: {len(states) - 1} steps" +
          (f", loop to {loop}" if loop is not None else ""))


if __name__ == "__main__":
    main()
