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
  # A search big enough for two ranks to pay (about 2-3 s serially on one core of this kind of
  # machine): 6D Dijkstra with the ownership measured best there, two contiguous slabs
  # (docs/PERFORMANCE.md, "Slab ownership").
  mpirun -np 2 --oversubscribe build/bin/hpcplan grid --dims 6 --extent 11 --algo dijkstra \
    --owner-slabs 6 --compare-serial --json
} | python3 scripts/grid_table.py
