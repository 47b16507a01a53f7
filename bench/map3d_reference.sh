#!/usr/bin/env bash
# The stand-in for the optimum on every shipped box map: the best of RUNS long RRT* runs
# (informed sampling), each shortcut and tightened. Writes results/map3d/reference.csv.
# Usage: bench/map3d_reference.sh [RUNS=3] [SECONDS=30]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
seconds=${2:-30}
bin=build/bin/hpcplan
out=results/map3d
mkdir -p "$out"
tmp=$(mktemp)
echo "map,seed,seconds,length,raw_length,tree_size" >"$tmp"
for map in bench/maps/*.txt; do
  name=$(basename "$map" .txt)
  [[ $name == sphere_* ]] && continue
  for seed in $(seq 1 "$runs"); do
    "$bin" map3d --map "$map" --algo rrtstar --time "$seconds" --seed "$seed" --shortcut --json |
      /usr/bin/python3 -c "import json,sys; j=json.load(sys.stdin); print(f\"$name,$seed,$seconds,{j['length']:.9f},{j['raw_length']:.9f},{j['tree_size']}\")" >>"$tmp"
    echo "reference: $name seed $seed done" >&2
  done
done
mv "$tmp" "$out/reference.csv"
