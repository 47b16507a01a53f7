#!/usr/bin/env python3
"""Reads `hpcplan grid --json` objects (one per line) on stdin and prints a table.

Distributed runs add the scheme, the workload deviation (max - min share of expansions,
seed 002 Table IV), messages sent, and, with --compare-serial, the serial cost, search
overhead and speedup measured in the same job."""
import json
import sys

rows = [json.loads(line) for line in sys.stdin if line.strip()]
header = (f"{'d':>3} {'algo':>8} {'ranks':>5} {'scheme':>10} {'status':>9} {'cost':>9} {'quality':>7} "
          f"{'expanded':>9} {'time ms':>8} {'dev %':>6} {'msgs':>6} {'serial':>9} {'overhead':>8} {'speedup':>7}")
print(header)
print("-" * len(header))
for r in rows:
    cost = f"{r['cost']:.3f}" if r["cost"] is not None else "-"
    quality = f"{r['quality']:.4f}" if r["quality"] is not None else "-"
    dist = r.get("distributed")
    dev = f"{dist['workload_deviation_percent']:.2f}" if dist else "-"
    msgs = f"{dist['messages_sent']}" if dist else "-"
    ref = r.get("serial_reference")
    serial = f"{ref['cost']:.3f}" if ref and ref["cost"] is not None else "-"
    overhead = f"{ref['search_overhead']:.3f}" if ref and ref["search_overhead"] is not None else "-"
    speedup = f"{ref['speedup']:.2f}x" if ref and ref["speedup"] is not None else "-"
    print(f"{r['dims']:>3} {r['algo']:>8} {r['ranks']:>5} {r['scheme']:>10} {r['status']:>9} {cost:>9} "
          f"{quality:>7} {r['expanded']:>9} {r['time_ms']:>8.2f} {dev:>6} {msgs:>6} {serial:>9} "
          f"{overhead:>8} {speedup:>7}")
if any(r.get("serial_reference") for r in rows):
    print()
    print("The seed's default problems take milliseconds: at that size the ranks spend more time starting,\n"
          "exchanging states and agreeing to stop than searching (and A* explores more states when the\n"
          "order of expansion is spread over ranks).")
    last = rows[-1].get("serial_reference") or {}
    if last.get("speedup") is not None and rows[-1].get("distributed"):
        print(f"The last row, a search of seconds, ran {last['speedup']:.2f}x the serial engine on "
              f"{rows[-1]['ranks']} ranks, with workload deviation "
              f"{rows[-1]['distributed']['workload_deviation_percent']:.1f}%.\n"
              "Two serial searches at once ran 1.3-2.4x one search's speed (medians of rounds) on the 2-core VMs\n"
              "(the machine's own ceiling; docs/PERFORMANCE.md, issue 17).")
