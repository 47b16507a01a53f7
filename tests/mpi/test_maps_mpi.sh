#!/usr/bin/env bash
# Maps users bring, under the real Open MPI: every distributed engine on MovingAI maps and an
# N-dimensional .npy equals the serial optimum for 1, 2, 3 and 4 ranks (sparse A* and Dijkstra
# by hashed ownership, HDA* and bulk, and by slabs; the dense engine's slabs for Dijkstra and BFS), and
# `hpcplan scen` under mpirun (rows dealt round the ranks, and every rank on each row) answers
# every row it runs with the published optimum, its rows equal to the serial run's.
# Usage: bash tests/mpi/test_maps_mpi.sh path/to/hpcplan MOVINGAI_DIR
set -euo pipefail
bin=$1
dir=$2
py=/usr/bin/python3
[[ -d $dir ]] || { echo "test_maps_mpi: the MovingAI folder '$dir' is missing" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
mpi() { timeout 300 mpirun -np "$1" --oversubscribe "${@:2}"; }

# A 4D array with random obstacles (30%), its shape not a hypercube.
"$py" - "$tmp/c4.npy" <<'PY'
import numpy as np, sys
rng = np.random.default_rng(4)
np.save(sys.argv[1], (rng.random((7, 9, 8, 11)) < 0.3).astype(np.uint8))
PY
"$py" - "$tmp/c4.npy" >"$tmp/ends" <<'PY'
import numpy as np, sys
a = np.load(sys.argv[1])
free = np.argwhere(a == 0)
s, g = free[0][::-1], free[-1][::-1]  # x first
print(",".join(map(str, s)), ",".join(map(str, g)))
PY
read -r s4 g4 <"$tmp/ends"

cases=(
  "--map $dir/Boston_0_256.map --start 188,1 --goal 12,231 --algo astar"
  "--map $dir/Boston_0_256.map --start 135,10 --goal 7,255 --algo dijkstra --engine sparse"
  "--map $dir/Boston_0_256.map --start 135,10 --goal 7,255 --algo dijkstra --engine sparse --mode bulk"
  "--map $dir/64room_005.map --start 15,92 --goal 470,300 --algo dijkstra --engine dense"
  "--map $dir/64room_005.map --start 15,92 --goal 470,300 --algo astar --owner-slabs 16"
  "--map $dir/maze512-4-6.map --start 15,92 --goal 17,189 --algo bfs --engine dense"
  "--map $tmp/c4.npy --start $s4 --goal $g4 --algo astar"
  "--map $tmp/c4.npy --start $s4 --goal $g4 --algo dijkstra --engine dense"
  "--map $tmp/c4.npy --start $s4 --goal $g4 --algo bfs --engine sparse"
)
for i in "${!cases[@]}"; do
  c=${cases[$i]}
  # shellcheck disable=SC2086
  serial=$("$bin" grid $c --json)
  # Each case on 2 ranks; sparse A* (hashed), sparse bulk Dijkstra, and dense Dijkstra's slabs
  # on a map and on the 4D array on 1, 3 and 4 as well (each mpirun start costs a second).
  ranks="2"
  ((i == 0 || i == 2 || i == 3 || i == 7)) && ranks="1 2 3 4"
  for np in $ranks; do
    rc=0
    # shellcheck disable=SC2086
    got=$(mpi "$np" "$bin" grid $c --json) || rc=$?
    if ((rc != 0)); then
      echo "test_maps_mpi: FAIL grid $c on $np ranks: exit $rc" >&2
      fail=1
      continue
    fi
    "$py" - "$c" "$np" "$serial" "$got" <<'PY' || fail=1
import json, sys
case, np_, s, d = sys.argv[1], int(sys.argv[2]), json.loads(sys.argv[3]), json.loads(sys.argv[4])
ok = d["status"] == s["status"] == "solved" and d["ranks"] == np_
ok = ok and abs(d["cost"] - s["cost"]) <= 1e-9 * (1 + s["cost"])
if "--algo bfs" in case:
    ok = ok and d["hops"] == s["hops"]
if not ok:
    print(f"test_maps_mpi: FAIL {case} on {np_} ranks: serial {s['status']} {s.get('cost')}, "
          f"distributed {d['status']} {d.get('cost')} ({d.get('engine')})", file=sys.stderr)
sys.exit(0 if ok else 1)
PY
  done
done

# Scenario runs: every 7th bucket of Boston (rows dealt round 2 and 3 ranks) and a few rows with
# the distributed planner on each; each run's rows equal to the serial run's, costs exactly.
"$bin" scen "$dir/Boston_0_256.map.scen" --buckets 0-20 --csv "$tmp/serial.csv" --json >"$tmp/serial.json"
for np in 2 3; do
  mpi "$np" "$bin" scen "$dir/Boston_0_256.map.scen" --buckets 0-20 --csv "$tmp/rows$np.csv" \
    --json >"$tmp/rows$np.json" || { echo "test_maps_mpi: FAIL scen on $np ranks" >&2; fail=1; }
done
mpi 2 "$bin" scen "$dir/random512-40-5.map.scen" --buckets 100-101 --split search --algo astar \
  --csv "$tmp/search.csv" --json >"$tmp/search.json" ||
  { echo "test_maps_mpi: FAIL scen --split search" >&2; fail=1; }
"$py" - "$tmp" <<'PY' || fail=1
import csv, json, sys
t = sys.argv[1]
def rows(name):
    with open(f"{t}/{name}.csv") as f:
        return [(r["row"], r["cost"], r["status"]) for r in csv.DictReader(f)]
ok = True
serial = rows("serial")
for name, ranks, split in (("rows2", 2, "rows"), ("rows3", 3, "rows"), ("search", 2, "search")):
    j = json.load(open(f"{t}/{name}.json"))
    if j["ranks"] != ranks or j["split"] != split or j["mismatches"] != 0 or j["rows"] == 0:
        print(f"test_maps_mpi: FAIL {name}: {j['ranks']} ranks, split {j['split']}, "
              f"{j['rows']} rows, {j['mismatches']} mismatches", file=sys.stderr)
        ok = False
    if name != "search" and rows(name) != serial:
        print(f"test_maps_mpi: FAIL {name}: its rows differ from the serial run's", file=sys.stderr)
        ok = False
sys.exit(0 if ok else 1)
PY

# A wrong published length is a failed run under mpirun too (exit 1, the row named).
awk 'NR==1 || NR==2 {print} NR==2 {sub(/[0-9.]+$/, "1.0"); print}' "$dir/Boston_0_256.map.scen" |
  head -2 >"$tmp/wrong.scen"
printf '%s\n' "$(sed -n 2p "$dir/Boston_0_256.map.scen" | awk -F'\t' 'BEGIN{OFS="\t"} {$9="1.0"; print}')" >>"$tmp/wrong.scen"
cp "$dir/Boston_0_256.map" "$tmp/"
rc=0
mpi 2 "$bin" scen "$tmp/wrong.scen" >"$tmp/wrong.out" 2>"$tmp/wrong.err" || rc=$?
if ((rc != 1)) || ! grep -q "differ from the published optimum" "$tmp/wrong.err"; then
  echo "test_maps_mpi: FAIL a wrong published length: exit $rc, $(cat "$tmp/wrong.err")" >&2
  fail=1
fi
# A bad row (a blocked start) dealt to rank 1: every rank refuses it before any runs (exit 2),
# none is left waiting in the gather.
{ head -2 "$dir/Boston_0_256.map.scen"; sed -n 3p "$dir/Boston_0_256.map.scen" |
  awk -F'\t' 'BEGIN{OFS="\t"} {$5="21"; $6="0"; print}'; } >"$tmp/Boston_0_256.map.scen"
rc=0
mpi 2 "$bin" scen "$tmp/Boston_0_256.map.scen" >/dev/null 2>"$tmp/bad.err" || rc=$?
if ((rc != 2)) || ! grep -q "scenario row 1: its start is blocked" "$tmp/bad.err"; then
  echo "test_maps_mpi: FAIL a bad row under mpirun: exit $rc, $(head -3 "$tmp/bad.err")" >&2
  fail=1
fi
((fail == 0)) && echo "test_maps_mpi: every distributed answer equals the serial optimum"
exit "$fail"
