#!/usr/bin/env bash
# Every planner on every shipped box map, RUNS seeds each, against the reference lengths of
# bench/map3d_reference.sh: writes results/map3d/sweep.csv, the example paths under
# results/map3d/paths, and prints the Markdown tables of docs/PERFORMANCE.md.
# Usage: bench/map3d_sweep.sh [RUNS=5] [SECONDS=1]   (run map3d_reference.sh first)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
seconds=${2:-1}
out=results/map3d
[[ -f $out/reference.csv ]] || { echo "map3d_sweep: run bench/map3d_reference.sh first" >&2; exit 2; }
configs=astar@0.1,astar@0.1+shortcut,wastar@0.1,thetastar@0.1+shortcut,astar@0.25+shortcut
configs+=,thetastar@0.25+shortcut,thetastar@0.5+shortcut,visgraph,visgraph+shortcut
configs+=,visgraph@0.25+shortcut,rrt+shortcut,birrt+shortcut,rrtstar,rrtstar+shortcut
configs+=,ompl:rrtconnect+shortcut,ompl:bitstar,ompl:informedrrtstar
maps=()
for name in single_box maze thin_walls tower window forest; do maps+=("bench/maps/$name.txt"); done
mkdir -p "$out/paths"
build/bin/hpcplan_world_sweep --kind map3d --maps "${maps[@]}" --configs "$configs" \
  --runs "$runs" --time "$seconds" --out "$out/sweep.csv" --paths "$out/paths"
/usr/bin/python3 scripts/world_tables.py map3d "$out/sweep.csv" "$out/reference.csv"
