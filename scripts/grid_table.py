#!/usr/bin/env python3
"""Reads `hpcplan grid --json` objects (one per line) on stdin and prints a table."""
import json
import sys

rows = [json.loads(line) for line in sys.stdin if line.strip()]
header = f"{'d':>3} {'ranks':>5} {'status':>15} {'blocked':>8} {'cost':>10} {'quality':>8} {'expanded':>10} {'generated':>11} {'time ms':>9}"
print(header)
print("-" * len(header))
for r in rows:
    cost = f"{r['cost']:.3f}" if r["cost"] is not None else "-"
    quality = f"{r['quality']:.4f}" if r["quality"] is not None else "-"
    print(f"{r['dims']:>3} {r['ranks']:>5} {r['status']:>15} {100 * r['blocked_fraction']:>7.1f}% {cost:>10} "
          f"{quality:>8} {r['expanded']:>10} {r['generated']:>11} {r['time_ms']:>9.2f}")
