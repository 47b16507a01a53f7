#!/usr/bin/env bash
# hpcplan grid --world chain|hypercube from the command line: the answer and its path in the
# space's own coordinates (radians, [0, 1]), re-checked here against the definition's geometry
# (each step's wrapped length sums to the cost), the same cost from two MPI ranks, and every
# bad option refused in one line with exit 2.
# Usage: bash tests/cli/test_cspace_cli.sh path/to/hpcplan [mpirun]
set -uo pipefail
bin=$1
mpirun=${2:-mpirun}
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

expect() {
  local code=$1 word=$2
  shift 2
  local rc=0
  timeout 120 "$bin" "$@" >"$tmp/out" 2>"$tmp/err" || rc=$?
  if ((rc != code)); then
    echo "test_cspace_cli: FAIL (exit $rc, not $code): hpcplan $* :: $(head -c 300 "$tmp/err")" >&2
    fail=1
    return
  fi
  if [[ -n $word ]]; then
    if [[ $(wc -l <"$tmp/err") -ne 1 ]] || ! grep -qF -- "$word" "$tmp/err"; then
      echo "test_cspace_cli: FAIL (not one line naming '$word'): hpcplan $* :: $(cat "$tmp/err")" >&2
      fail=1
    fi
  fi
}

# The answers: the path's states in the space's coordinates, from the benchmark's start to its
# goal, each step's length (periodic axes the short way) summing to the cost.
for case in "chain 5" "hypercube 6"; do
  set -- $case
  expect 0 "" grid --world "$1" --dims "$2" --path --json --output "$tmp/$1.json"
  "$py" - "$tmp/out" "$1" "$2" <<'PY' || fail=1
import json, math, sys
j = json.load(open(sys.argv[1]))
world, n = sys.argv[2], int(sys.argv[3])
assert j["status"] == "solved", j["status"]
cs = j["cspace"]
assert cs["path_rechecked"] and len(cs["periodic"]) == n
path = j["path_states"]
if world == "chain":
    start = [0.0] + [math.pi / n] * (n - 1)
    goal = [math.pi - 0.001] + [0.0] * (n - 1)
    assert all(cs["periodic"])
    assert all(-math.pi <= v < math.pi for q in path for v in q)
else:
    start, goal = [0.0] * n, [1.0] * n
    assert not any(cs["periodic"])
    assert all(0.0 <= v <= 1.0 for q in path for v in q)
assert max(abs(a - b) for a, b in zip(path[0], start)) < 1e-12, path[0]
assert max(abs(a - b) for a, b in zip(path[-1], goal)) < 1e-12, path[-1]
def step(a, b, periodic):
    d = b - a
    if periodic:
        d = (d + math.pi) % (2 * math.pi) - math.pi
    return d
length = sum(math.sqrt(sum(step(a, b, p) ** 2 for a, b, p in zip(x, y, cs["periodic"])))
             for x, y in zip(path, path[1:]))
assert abs(length - j["cost"]) < 1e-9, (length, j["cost"])
PY
  cmp -s "$tmp/out" "$tmp/$1.json" || { echo "test_cspace_cli: FAIL --output differs" >&2; fail=1; }
done

# Two ranks: the serial engine's cost.
serial=$("$bin" grid --world chain --dims 5 --json | "$py" -c 'import json,sys; print(json.load(sys.stdin)["cost"])')
ranks=$(timeout 300 "$mpirun" -np 2 --oversubscribe "$bin" grid --world chain --dims 5 --json |
  "$py" -c 'import json,sys; j=json.load(sys.stdin); assert j["ranks"] == 2; print(j["cost"])')
[[ $serial == "$ranks" ]] || { echo "test_cspace_cli: FAIL 2 ranks cost $ranks, serial $serial" >&2; fail=1; }

# Bad input: one line, exit 2.
expect 2 "--dims for chain must be in 2..16" grid --world chain --dims 1
expect 2 "unknown configuration space 'arm'" grid --world arm --dims 4
expect 2 "--dims is required with --world" grid --world chain
expect 2 "in collision" grid --world chain --dims 2
expect 2 "in collision" grid --world hypercube --dims 4 --start 0.5,0.5,0.5,0.5
expect 2 "--goal needs 3 values" grid --world chain --dims 3 --goal 1,2
expect 2 "outside the bounds" grid --world hypercube --dims 3 --goal 1,1,2
expect 2 "--start must be numbers" grid --world chain --dims 3 --start 1,x,2
expect 2 "--cells must be in 3..65535" grid --world chain --dims 3 --cells 2
expect 2 "--world and --map are two worlds" grid --world chain --dims 3 --map "$0"
expect 2 "--density describes the GOG field" grid --world chain --dims 3 --density 0.3
expect 2 "--connectivity is the GOG lattice's" grid --world chain --dims 3 --connectivity full
expect 2 "--engine dense plans on GOG" grid --world chain --dims 3 --engine dense
expect 2 "unknown --moves" grid --world chain --dims 3 --moves diagonal
expect 2 "give --world" grid --dims 3 --cells 10
expect 2 "unknown --checks" grid --world chain --dims 3 --checks simd
expect 2 "give --world" grid --dims 3 --checks single
expect 2 "--owner-slabs and --owner-cuts" grid --world chain --dims 3 --owner-slabs 2
expect 2 "--field-out writes a GOG or map" grid --world chain --dims 3 --algo bfs --field-out "$tmp/f.npy"
expect 2 "--simulate-ranks predicts GOG" grid --world chain --dims 3 --simulate-ranks 2

exit $fail
