#!/usr/bin/env python3
"""Turns one `hpcplan grid --json` result (stdin) into a row of the `hpcplan ompl` CSV, so the
distributed grid planner sits in the same tables as the OMPL planners.
Usage: hpcplan grid ... --json | grid_json_to_csv.py PLANNER RUN"""
import json
import sys

planner, run = sys.argv[1], sys.argv[2]
d = json.load(sys.stdin)
ok = d["status"] == "solved"
t = d["time_ms"] / 1e3


def f(x):
    return f"{x:.6f}" if ok else ""


print(",".join([planner, str(d["dims"]), run, str(d["seed"]), "1" if ok else "0",
                f(t), f(d["cost"]), f(d["quality"]), "", "", f(d["quality"]), f(d["cost"]),
                f"{t:.6f}", str(d["collision_checks"]), "1", ""]))
