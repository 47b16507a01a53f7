#!/usr/bin/env bash
# Before/after in one session: the same figures from two build trees, interleaved round by round
# (the order alternates), so machine drift hits both alike. Figures: generation throughput at 6D
# (Google Benchmark), the seed's default problems d = 2..10, 2-rank 6D Dijkstra under mpirun, and
# the deterministic map3d configurations (grid searches, Theta*, visibility graph) on every
# shipped map. Prints medians per build and the median of the per-round new/old ratios; raw
# rows in results/compare.csv.
# Usage: bench/compare_builds.sh OLD_BUILD_DIR NEW_BUILD_DIR [ROUNDS=5]
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1
new=$2
rounds=${3:-5}
[[ -x $old/bin/hpcplan && -x $new/bin/hpcplan ]] || { echo "compare_builds: need two build trees with bin/hpcplan" >&2; exit 2; }
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
mkdir -p results
out=results/compare.csv
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "round,build,figure,value" >"$tmp/rows.csv"
maps=()
for name in single_box maze thin_walls tower window forest; do maps+=("bench/maps/$name.txt"); done
configs=astar@0.1,astar@0.25+shortcut,thetastar@0.25+shortcut,visgraph,visgraph+shortcut
measure() {  # round build dir
  local r=$1 b=$2 d=$3
  "$d/bin/hpcplan_bench" --benchmark_filter='Throughput/absl/6/' \
    --benchmark_format=json 2>/dev/null | python3 -c "
import json,sys
for x in json.load(sys.stdin)['benchmarks']: print('$r,$b,generated_per_s_6d,%g' % x['generated_per_s'])" >>"$tmp/rows.csv"
  "$d/bin/hpcplan_bench" --benchmark_filter='DefaultProblem' --benchmark_format=json 2>/dev/null |
    python3 -c "
import json,sys
for x in json.load(sys.stdin)['benchmarks']: print('$r,$b,default_ms_d%s,%g' % (x['name'].split('/')[1], x['real_time']))" >>"$tmp/rows.csv"
  mpirun -np 2 --oversubscribe "$d/bin/hpcplan" grid --dims 6 --extent 11 --algo dijkstra \
    --mode bulk --owner-coarsen 1 --json | python3 -c "
import json,sys; print('$r,$b,mpi2_dijkstra_6d_ms,%g' % json.load(sys.stdin)['time_ms'])" >>"$tmp/rows.csv"
  "$d/bin/hpcplan_world_sweep" --kind map3d --maps "${maps[@]}" --configs "$configs" --runs 1 \
    --out "$tmp/sweep.csv" >/dev/null 2>&1
  python3 -c "
import csv
for row in csv.DictReader(open('$tmp/sweep.csv')):
    print('$r,$b,map3d_%s_%s_ms,%s' % (row['map'], row['config'], row['time_ms']))
    print('$r,$b,map3d_%s_%s_length,%s' % (row['map'], row['config'], row['length']))" >>"$tmp/rows.csv"
}
for ((r = 1; r <= rounds; r++)); do
  if ((r % 2)); then measure "$r" old "$old"; measure "$r" new "$new"
  else measure "$r" new "$new"; measure "$r" old "$old"; fi
  echo "compare_builds: round $r/$rounds done" >&2
done
cp "$tmp/rows.csv" "$out"
python3 - "$out" <<'PY'
import csv, statistics, sys
from collections import defaultdict
vals = defaultdict(lambda: defaultdict(dict))  # figure -> build -> round -> value
for row in csv.DictReader(open(sys.argv[1])):
    vals[row["figure"]][row["build"]][row["round"]] = float(row["value"])
# The ratio is taken within each round (both builds ran minutes apart, in alternating order)
# and the median of those ratios is reported: this VM drifts by tens of percent between rounds.
print("| figure | old (median) | new (median) | new / old (median of per-round ratios) |")
print("|---|---|---|---|")
for fig, by in vals.items():
    rounds = sorted(set(by["old"]) & set(by["new"]))
    ratios = [by["new"][r] / by["old"][r] for r in rounds if by["old"][r]]
    o, n = statistics.median(by["old"].values()), statistics.median(by["new"].values())
    ratio = statistics.median(ratios) if ratios else float("nan")
    print(f"| {fig} | {o:.6g} | {n:.6g} | {ratio:.3f} |")
PY
