#!/usr/bin/env bash
# The main job: install, build, and solve seed 002's default problems for d = 2..10 on two MPI
# ranks (hash-distributed A*), each checked against the serial engine in the same job, plus
# a level-synchronous BFS and one search large enough for the ranks to pay; prints one table.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh build >/dev/null
# Open MPI refuses to run as root unless told that this is intended.
if [[ $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
echo "hpcplan: grid search on the GOG field over 2 MPI ranks (mpirun -np 2), start/goal corners adjusted until free"
{
  for d in 2 4 6 8 10; do
    mpirun -np 2 --oversubscribe build/bin/hpcplan grid --dims "$d" --compare-serial --json
  done
  mpirun -np 2 --oversubscribe build/bin/hpcplan grid --dims 3 --algo bfs --compare-serial --json
  # A search big enough for two ranks to pay (about 1-3 s serially on one core of this kind of
  # machine): 6D Dijkstra with the ownership measured best there, prefix cuts placed by the
  # rank simulation where a serial run's expansions split evenly (docs/PERFORMANCE.md, "Prefix
  # cuts balanced on a serial run"); two slabs would split the work 63 : 37.
  big=(--dims 6 --extent 11 --algo dijkstra)
  cuts=$(build/bin/hpcplan grid "${big[@]}" --simulate-ranks 2 --simulate-coarsen 0 --json |
    python3 -c "import json, sys; print(*json.load(sys.stdin)['rank_simulation'][0]['balanced_prefix_cuts'], sep=',')")
  mpirun -np 2 --oversubscribe build/bin/hpcplan grid "${big[@]}" --owner-cuts "$cuts" \
    --compare-serial --json
} | python3 scripts/grid_table.py
