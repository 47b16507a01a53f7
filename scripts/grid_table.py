#!/usr/bin/env python3
"""Reads `hpcplan grid --json` objects (one per line) on stdin and prints a table.

The "rank x thr" column is the ranks times each rank's threads (the dense engine's OpenMP
threads; one for the other engines).

Distributed runs add the scheme, the workload deviation (max - min share of expansions,
seed 002 Table IV), messages sent, and, with --compare-serial, the serial cost, search
overhead and speedup measured in the same job."""
import json
import sys

rows = [json.loads(line) for line in sys.stdin if line.strip()]
header = (f"{'world':>17} {'d':>3} {'extent':>6} {'algo':>8} {'rank x thr':>10} {'scheme':>10} {'status':>9} {'cost':>9} {'quality':>7} "
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
    world = r.get("world", r.get("obstacles", "gog"))
    # Processes x threads each: the dense engine's OpenMP threads per rank (the rank's share
    # of its CPU set by default), one for the other engines.
    procs = f"{r['ranks']}x{r['dense']['threads'] if r.get('dense') else 1}"
    print(f"{world:>17} {r['dims']:>3} {r['extent']:>6} {r['algo']:>8} {procs:>10} {r['scheme']:>10} {r['status']:>9} {cost:>9} "
          f"{quality:>7} {r['expanded']:>9} {r['time_ms']:>8.2f} {dev:>6} {msgs:>6} {serial:>9} "
          f"{overhead:>8} {speedup:>7}")
if any(r.get("serial_reference") for r in rows):
    print()
    print("The seed's default problems take milliseconds: at that size the ranks spend more time starting,\n"
          "exchanging states and agreeing to stop than searching (and A* explores more states when the\n"
          "order of expansion is spread over ranks).")
    # Rows whose serial search took long enough for the ranks to pay back their start-up and
    # exchanges.
    big = [r for r in rows if r.get("distributed") and (r.get("serial_reference") or {}).get("speedup")
           and r["serial_reference"].get("time_ms", 0) >= 300]
    for r in big:
        ref = r["serial_reference"]
        where = r.get("world", r.get("obstacles", "gog"))
        print(f"{where} {r['dims']}D extent {r['extent']} {r['algo']} ({ref['time_ms']:.0f} ms serially): "
              f"{ref['speedup']:.2f}x on {r['ranks']} ranks ({r['scheme']}), workload deviation "
              f"{r['distributed']['workload_deviation_percent']:.1f}%.")
    if big:
        print("Two serial searches at once ran 1.3-2.4x one search's speed (medians of rounds) on the 2-core VMs\n"
              "(the machine's own ceiling; docs/PERFORMANCE.md, issues 17 and 31).")
