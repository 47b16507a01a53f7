#!/usr/bin/env bash
# The stand-in for the optimum on every shipped box map: the best of RUNS long RRT* runs
# (informed sampling), each shortcut and tightened. A cross-check is recorded beside it: the
# visibility graph over bend points SPACING apart (default 0.05 m), tightened; the tables take
# the shorter of the two as the best known length. Writes results/map3d/reference.csv.
# Usage: bench/map3d_reference.sh [RUNS=3] [SECONDS=30] [SPACING=0.05]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
seconds=${2:-30}
spacing=${3:-0.05}
bin=build/bin/hpcplan
out=results/map3d
mkdir -p "$out"
tmp=$(mktemp)
echo "map,planner,seed,seconds,length,raw_length,tree_size" >"$tmp"
row() {  # map planner seed seconds, JSON on stdin
  /usr/bin/python3 -c "import json,sys; j=json.load(sys.stdin); print(f\"$1,$2,$3,$4,{j['length']:.9f},{j['raw_length']:.9f},{j['tree_size']}\")"
}
for map in bench/maps/*.txt; do
  name=$(basename "$map" .txt)
  [[ $name == sphere_* ]] && continue
  for seed in $(seq 1 "$runs"); do
    "$bin" map3d --map "$map" --algo rrtstar --time "$seconds" --seed "$seed" --shortcut --json |
      row "$name" rrtstar "$seed" "$seconds" >>"$tmp"
    echo "reference: $name rrtstar seed $seed done" >&2
  done
  "$bin" map3d --map "$map" --algo visgraph --spacing "$spacing" --shortcut --json |
    row "$name" "visgraph@$spacing" 1 0 >>"$tmp"
done
mv "$tmp" "$out/reference.csv"
