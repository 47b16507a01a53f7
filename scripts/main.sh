#!/usr/bin/env bash
# The main job: install, build, and solve seed 002's default problems for d = 2..10,
# printing one readable table.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh build >/dev/null
echo "hpcplan: grid A* on the GOG field, default problems (start/goal corners, adjusted until free)"
for d in 2 4 6 8 10; do
  build/bin/hpcplan grid --dims "$d" --json
done | python3 scripts/grid_table.py
