#!/usr/bin/env bash
# hpcplan grid --field-out end to end: the .npy read back with NumPy (shape in NumPy order,
# dtype, -1 on every blocked cell and on unreachable ones, 0 at the start), its values at a few
# goals equal to what `hpcplan grid --json` answers for those goals (BFS: hops; Dijkstra: cost),
# serial and under mpirun -np 2 (the same bytes as the serial file); GOG fields too; bad input
# exits 2 with one line and writes nothing.
# Usage: test_field_out.sh HPCPLAN MAPS_DIR [MPIRUN]
set -uo pipefail
bin=$1
maps=$2
mpirun=${3:-}
# Under AddressSanitizer the ranks run without leak checks, as the MPI suites do
# (tests/mpi/CMakeLists.txt: Open MPI's components leak at start-up); the serial runs keep them.
mpi_asan=${ASAN_OPTIONS:+detect_leaks=0:abort_on_error=1}
py=/usr/bin/python3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "field_out: FAIL: $*" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Threads waiting at the engine's barriers sleep rather than spin: on a busy 2-core machine a
# spinning thread holds up the one it waits for.
export OMP_WAIT_POLICY=passive
map=$maps/Boston_0_256.map
[[ -f $map ]] || fail "$map is missing"
$py -c 'import numpy' 2>/dev/null || fail "$py has no numpy"
start=188,1
goals=(12,231 250,250 100,100 3,200)

check() {  # check FILE.npy ALGO: shape, dtype, -1 cells, values at the goals against --json
  local npy=$1 algo=$2 goal
  for goal in "${goals[@]}"; do
    "$bin" grid --map "$map" --start $start --goal "$goal" --algo "$algo" --engine sparse --json \
      >"$dir/q.json" || fail "grid --goal $goal --algo $algo failed"
    $py - "$npy" "$algo" "$goal" "$dir/q.json" "$map" <<'PY' || fail "$npy at $goal ($algo)"
import json, sys
import numpy as np
npy, algo, goal, q, path = sys.argv[1:6]
a = np.load(npy)
assert a.shape == (256, 256), a.shape
assert a.dtype == (np.int32 if algo == "bfs" else np.float32), a.dtype
rows = open(path).read().split("\n")[4:4 + 256]
blocked = np.array([[c not in ".G" for c in r] for r in rows])
assert (a[blocked] == -1).all(), "a blocked cell has a value"
assert a[1, 188] == 0, a[1, 188]
x, y = map(int, goal.split(","))
r = json.load(open(q))
if r["status"] == "solved":
    want = r["hops"] if algo == "bfs" else r["cost"]
    assert abs(a[y, x] - want) <= 1e-4 * max(1, want), (goal, a[y, x], want)
else:
    assert a[y, x] == -1, (goal, a[y, x], r["status"])
# Unreachable free cells exist on this map (walled-in pockets): -1 too.
assert ((a == -1) & ~blocked).sum() > 0
PY
  done
}

for algo in bfs dijkstra; do
  out=$dir/$algo.npy
  "$bin" grid --map "$map" --start $start --algo $algo --field-out "$out" --json >"$dir/run.json" ||
    fail "--field-out ($algo) failed"
  $py - "$dir/run.json" "$out" <<'PY' || fail "the report of --field-out ($algo)"
import json, sys
import numpy as np
r = json.load(open(sys.argv[1]))
f = r["distance_field"]
a = np.load(sys.argv[2])
assert f["file"] == sys.argv[2] and f["written"] and f["complete"], f
assert f["reached"] == int((a >= 0).sum()) and f["shape"] == [256, 256], f
assert r["engine"] == "dense", r["engine"]
PY
  check "$out" $algo
  # With a goal: reported, and the field the same.
  "$bin" grid --map "$map" --start $start --goal 12,231 --algo $algo --threads 2 \
    --field-out "$dir/goal.npy" --json >"$dir/run.json" || fail "--field-out --goal ($algo)"
  cmp -s "$out" "$dir/goal.npy" || fail "the field with --goal differs ($algo)"
  $py -c "import json,sys; r=json.load(open('$dir/run.json')); assert r['status']=='solved' and r['goal']==[12,231] and r['distance_field']['goal_given'], r" ||
    fail "--goal not reported ($algo)"
  if [[ -n $mpirun ]]; then
    ASAN_OPTIONS=${mpi_asan:-${ASAN_OPTIONS:-}} timeout 120 "$mpirun" -np 2 "$bin" grid --map "$map" --start $start --algo $algo --threads 1 \
      --field-out "$dir/mpi.npy" >"$dir/mpi.txt" || fail "--field-out under mpirun -np 2 ($algo): exit $?"
    cmp -s "$out" "$dir/mpi.npy" || fail "the two-rank field differs from the serial one ($algo)"
    grep -q "field      $dir/mpi.npy" "$dir/mpi.txt" || fail "the summary names no field: $(cat "$dir/mpi.txt")"
  fi
done

# A GOG field (3D, full connectivity): shape (extent,)*3, the start's value 0.
"$bin" grid --dims 3 --extent 20 --connectivity full --algo dijkstra --field-out "$dir/gog.npy" \
  >/dev/null || fail "--field-out on GOG"
$py -c "import numpy as np; a=np.load('$dir/gog.npy'); assert a.shape==(20,20,20) and a.dtype==np.float32 and a[0,0,0]==0 and (a>0).sum()>1000, (a.shape, (a>0).sum())" ||
  fail "the GOG field"

# Bad input: exit 2, one line, nothing written.
bad() {
  local expect=$1
  shift
  "$bin" grid --map "$map" "$@" >"$dir/out" 2>"$dir/err"
  local rc=$?
  ((rc == 2)) || fail "'$*': exit $rc, not 2 ($(cat "$dir/err"))"
  [[ $(wc -l <"$dir/err") -eq 1 ]] || fail "'$*': not one error line: $(cat "$dir/err")"
  grep -q -- "$expect" "$dir/err" || fail "'$*': '$expect' not in: $(cat "$dir/err")"
  [[ ! -s $dir/out ]] || fail "'$*' wrote output"
}
bad "needs --algo bfs or dijkstra" --start $start --algo astar --field-out "$dir/x.npy"
bad "needs --algo bfs or dijkstra" --start $start --algo wastar --field-out "$dir/x.npy"
bad "drop --engine sparse" --start $start --algo bfs --engine sparse --field-out "$dir/x.npy"
bad "no --checkpoint" --start $start --algo bfs --checkpoint "$dir/c" --field-out "$dir/x.npy"
bad "does not exist" --start $start --algo bfs --field-out "$dir/no/such/dir/x.npy"
bad "inside an obstacle" --algo bfs --start 21,0 --field-out "$dir/x.npy"
[[ ! -e $dir/x.npy ]] || fail "a refused run wrote the field"
if [[ -n $mpirun ]]; then
  ASAN_OPTIONS=${mpi_asan:-${ASAN_OPTIONS:-}} timeout 60 "$mpirun" -np 2 "$bin" grid --map "$map" --start $start --algo astar \
    --field-out "$dir/x.npy" >"$dir/out" 2>"$dir/err"
  rc=$?
  ((rc == 2)) || fail "--algo astar --field-out under mpirun: exit $rc, not 2"
  grep -q "needs --algo bfs or dijkstra" "$dir/err" || fail "under mpirun: $(cat "$dir/err")"
fi
echo "field_out: ok"
