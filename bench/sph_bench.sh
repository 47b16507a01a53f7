#!/usr/bin/env bash
# The fluid's speed: ms per frame (the CLI, frames of 0.02 s) of the seed preset's dynamic
# scenario, and particle-steps/s of one substep (Google Benchmark) for both presets, at
# N = 1,500 / 12,500 / 25,000 / 100,000 / 1,000,000 with 1 and 2 threads; the thread counts
# alternate within each round and each figure is the median of ROUNDS rounds. Also the
# neighbour grid's build alone. Writes results/sph_bench.csv and prints Markdown tables
# (speedup = 1-thread time / 2-thread time, from the same rounds).
# Usage: bench/sph_bench.sh [BUILD_DIR=build] [ROUNDS=3]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
rounds=${2:-3}
for b in hpcplan hpcplan_bench_sph; do
  # (The test command's tree leaves the Google Benchmark programs out: HPCPLAN_BUILD_MICROBENCH.)
  [[ -x $build/bin/$b ]] || { echo "sph_bench: $build/bin/$b not found: build with bash scripts/build.sh $build" >&2; exit 2; }
done
mkdir -p results
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "round,what,preset,particles,threads,value" > "$tmp/rows.csv"
for r in $(seq "$rounds"); do
  for n in 1500 12500 25000 100000 1000000; do
    frames=$((n >= 1000000 ? 5 : n >= 100000 ? 20 : 60))
    for t in $([[ $((r % 2)) -eq 1 ]] && echo "1 2" || echo "2 1"); do
      "$build/bin/hpcplan" sph --preset seed --scenario dynamic --particles "$n" --frames "$frames" \
        --threads "$t" --json | python3 -c "
import json, sys
j = json.load(sys.stdin)
print('$r,ms_per_frame,seed,$n,$t,%g' % j['ms_per_frame_median'])
print('$r,grid_ms_per_frame,seed,$n,$t,%g' % j['grid_ms_per_frame_median'])" >> "$tmp/rows.csv"
    done
  done
  "$build/bin/hpcplan_bench_sph" --benchmark_format=json --benchmark_repetitions=1 2>/dev/null |
    python3 -c "
import json, sys
for b in json.load(sys.stdin)['benchmarks']:
    parts = b['name'].split('/')
    if parts[0] == 'Substep':
        preset = 'seed' if parts[1] == '0' else 'water'
        print('$r,substep_ms,%s,%s,%s,%g' % (preset, parts[2], parts[3], b['real_time']))
        print('$r,particle_steps_per_s,%s,%s,%s,%g' % (preset, int(b['particles']), parts[3], b['particle_steps_per_s']))
    elif parts[0] == 'GridBuild':
        print('$r,grid_build_ms,seed,%s,%s,%g' % (parts[1], parts[2], b['real_time']))" >> "$tmp/rows.csv"
done
cp "$tmp/rows.csv" results/sph_bench.csv
python3 - results/sph_bench.csv <<'PY'
import csv, statistics, sys
from collections import defaultdict
v = defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    v[(r["what"], r["preset"], r["particles"], r["threads"])].append(float(r["value"]))
med = {k: statistics.median(x) for k, x in v.items()}
def table(what, preset, unit, fmt, higher_is_better=False):
    ns = sorted({int(k[2]) for k in med if k[0] == what and k[1] == preset})
    print(f"\n{what} ({preset}, {unit}; medians of {len(next(iter(v.values())))} rounds)\n")
    last = "ns per particle-step, 2 threads" if higher_is_better else "ns per particle, 2 threads"
    print(f"| N | 1 thread | 2 threads | speedup | {last} |")
    print("|---|---|---|---|---|")
    for n in ns:
        a, b = med.get((what, preset, str(n), "1")), med.get((what, preset, str(n), "2"))
        if a is None or b is None: continue
        sp = b / a if higher_is_better else a / b
        per = 1e9 / b if higher_is_better else b / n * 1e6
        print(f"| {n:,} | {fmt % a} | {fmt % b} | {sp:.2f} | {per:.3g} |")
table("ms_per_frame", "seed", "ms per frame", "%.2f")
table("grid_ms_per_frame", "seed", "ms per frame in grid build and reordering", "%.2f")
table("grid_build_ms", "seed", "ms per grid build", "%.3f")
table("particle_steps_per_s", "seed", "particle-steps/s", "%.3g", True)
table("particle_steps_per_s", "water", "particle-steps/s", "%.3g", True)
PY
