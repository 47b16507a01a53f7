#!/usr/bin/env bash
# The main job: install, build, and solve seed 002's default problems for d = 2..10 on two MPI
# ranks (hash-distributed A*), each checked against the serial engine in the same job, plus
# a small BFS, two searches large enough for the ranks to pay (the dense engine's BFS and
# Dijkstra) and A* on OMPL's kinematic chain; prints one table.
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
  # Searches big enough for two ranks to pay (about 1-2 s serially on one core of this kind of
  # machine): the dense engine's slabs along the last axis, one per rank, exchanging one halo
  # layer per BFS level or Dijkstra bucket (docs/PERFORMANCE.md, issue 31).
  mpirun -np 2 --oversubscribe build/bin/hpcplan grid --dims 4 --extent 100 --algo bfs \
    --compare-serial --json
  mpirun -np 2 --oversubscribe build/bin/hpcplan grid --dims 4 --extent 60 --algo dijkstra \
    --compare-serial --json
  # OMPL's kinematic chain (7 links in the horn, 28 joint cells per axis): A* on the joint-space
  # lattice, where every successor costs a batch of segment tests (docs/CSPACE.md); the ranks
  # share the checks and the states.
  mpirun -np 2 --oversubscribe build/bin/hpcplan grid --world chain --dims 7 --cells 28 \
    --compare-serial --json
} | python3 scripts/grid_table.py
