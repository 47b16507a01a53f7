#!/usr/bin/env bash
# hpcplan map3d / sphere2d end to end: JSON contract, exact ends, path files, and bad input
# (exit 2, one line naming the problem), unreachable goals (exit 0, status no_path), nothing
# half-written.
set -euo pipefail
BIN=$1
MAPS=$2
PY=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# Every algorithm on one map: a solved, exactly-anchored path, re-checked here independently
# (segment by segment against the map's blocks with a dense sample).
check_path() {  # json map
  "$PY" - "$1" "$2" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
blocks, start, goal = [], None, None
for line in open(sys.argv[2]):
    w = line.split("#")[0].split()
    if not w: continue
    if w[0] == "block": blocks.append([float(x) for x in w[1:7]])
    if w[0] == "start": start = [float(x) for x in w[1:4]]
    if w[0] == "goal": goal = [float(x) for x in w[1:4]]
assert j["status"] == "solved", j["status"]
p = j["path"]
assert p[0] == start and p[-1] == goal, (p[0], p[-1])
length = 0.0
for a, b in zip(p, p[1:]):
    length += sum((x - y) ** 2 for x, y in zip(a, b)) ** 0.5
    for i in range(401):
        q = [x + (y - x) * i / 400 for x, y in zip(a, b)]
        for bl in blocks:
            assert not all(bl[k] <= q[k] <= bl[k + 3] for k in range(3)), (a, b, bl)
assert abs(length - j["length"]) < 1e-6 * length, (length, j["length"])
for key in ("algo", "time_ms", "expanded", "tree_size", "collision_checks"):
    assert key in j, key
PY
}
# --time is a guard here: every planner ends at its first path (RRT* with --stop-at-first), so
# no outcome depends on the machine's speed.
for algo in astar wastar dijkstra thetastar visgraph rrt birrt rrtstar ompl:rrtconnect; do
  first=""
  if [[ $algo == rrtstar || $algo == ompl:* ]]; then first=--stop-at-first; fi
  "$BIN" map3d --map "$MAPS/window.txt" --algo "$algo" --resolution 0.2 --time 60 $first --json >"$tmp/out.json" ||
    fail "map3d --algo $algo failed"
  check_path "$tmp/out.json" "$MAPS/window.txt" || fail "map3d --algo $algo returned a bad path"
done
"$BIN" map3d --map "$MAPS/single_box.txt" --algo thetastar --shortcut --path-out "$tmp/p.csv" --output "$tmp/o.json" >"$tmp/summary.txt"
grep -q "status *solved" "$tmp/summary.txt" || fail "summary lacks the status row"
head -1 "$tmp/p.csv" | grep -qx "x,y,z" || fail "path CSV header"
# The last row is the goal (9, 5, 5.2), read as numbers: exact, whatever the digits printed.
"$PY" -c "import csv,sys; r=list(csv.reader(open(sys.argv[1])))[-1]; assert [float(v) for v in r]==[9,5,5.2], r" \
  "$tmp/p.csv" || fail "path CSV does not end at the goal: $(tail -1 "$tmp/p.csv")"
"$PY" -c "import json; j=json.load(open('$tmp/o.json')); assert j['status']=='solved'"
# Explicit start and goal override the map's.
"$BIN" map3d --map "$MAPS/single_box.txt" --start 1,1,1 --goal 9,9,9 --json | "$PY" -c "import json,sys; j=json.load(sys.stdin); assert j['path'][0]==[1,1,1] and j['path'][-1]==[9,9,9]"

# Sphere world, every planner including the seed 003 hybrids.
for algo in astar thetastar visgraph hybrid hybrid_pick hybrid_sample rrtstar; do
  first=""
  if [[ $algo == rrtstar ]]; then first=--stop-at-first; fi
  "$BIN" sphere2d --map "$MAPS/sphere_world.txt" --algo "$algo" --time 60 $first --json >"$tmp/s.json" || fail "sphere2d $algo"
  "$PY" -c "import json; j=json.load(open('$tmp/s.json')); assert j['status']=='solved' and j['path'][0]==[-8,0] and j['path'][-1]==[8,0.5], j['path'][:1]"
done

# Bad input: exit 2, one line, naming the problem.
expect_bad() {  # mentions args...
  local mentions=$1; shift
  set +e
  "$BIN" "$@" >"$tmp/o" 2>"$tmp/e"
  local code=$?
  set -e
  [[ $code == 2 ]] || fail "expected exit 2 for: $* (got $code: $(cat "$tmp/e"))"
  [[ $(wc -l <"$tmp/e") == 1 ]] || fail "error is not one line for: $*"
  grep -q -- "$mentions" "$tmp/e" || fail "error for '$*' does not mention '$mentions': $(cat "$tmp/e")"
}
printf 'boundary 0 0 0 10 10 10\nblock 1 1 1 2 2\n' >"$tmp/bad.txt"
expect_bad "bad.txt:2:" map3d --map "$tmp/bad.txt" --start 0,0,0 --goal 9,9,9
printf 'boundary 0 0 0 10 10 10\r\nblock 1 1 1 2 2 oops\r\n' >"$tmp/crlf.txt"
expect_bad "crlf.txt:2: 'oops' is not a finite number" map3d --map "$tmp/crlf.txt" --start 0,0,0 --goal 9,9,9
expect_bad "inside the block of line" map3d --map "$MAPS/single_box.txt" --start 5,5,5
expect_bad "goal (11, 5, 5) is outside the boundary" map3d --map "$MAPS/single_box.txt" --goal 11,5,5
expect_bad "unknown algorithm 'dfs'" map3d --map "$MAPS/single_box.txt" --algo dfs
expect_bad "unknown algorithm 'ompl:nope' for map3d" map3d --map "$MAPS/single_box.txt" --algo ompl:nope
expect_bad "needs 3 comma-separated" map3d --map "$MAPS/single_box.txt" --start 1,2
# One coordinate too many, or a trailing comma, is refused too (both were once taken as x,y,z).
expect_bad "needs 3 comma-separated" map3d --map "$MAPS/single_box.txt" --start 1,2,3,4
expect_bad "needs 3 comma-separated" map3d --map "$MAPS/single_box.txt" --goal 9,5,5,
expect_bad "needs 2 comma-separated" sphere2d --map "$MAPS/sphere_world.txt" --start 1,1,999
expect_bad "resolution" map3d --map "$MAPS/single_box.txt" --resolution -1
expect_bad "resolution" map3d --map "$MAPS/single_box.txt" --resolution 50
expect_bad "weight" map3d --map "$MAPS/single_box.txt" --algo wastar --weight 0.5
expect_bad "time" map3d --map "$MAPS/single_box.txt" --algo rrt --time 0
expect_bad "spacing" map3d --map "$MAPS/single_box.txt" --algo visgraph --spacing -0.5
expect_bad "use a coarser --spacing" map3d --map "$MAPS/maze.txt" --algo visgraph --spacing 1e-7
printf 'boundary 0 0 0 10 10 10\n' >"$tmp/empty.txt"
expect_bad "no --start given" map3d --map "$tmp/empty.txt"
printf 'boundary 0 0 10\nsphere 1 2\n' >"$tmp/s.txt"
expect_bad "s.txt:2: sphere needs cx cy r" sphere2d --map "$tmp/s.txt" --start 0,0 --goal 1,1
expect_bad "inside the sphere of line" sphere2d --map "$MAPS/sphere_world.txt" --start 0,-1

# An unreachable goal is an answer: exit 0, status in the output (JSON and summary), a hint on
# stderr, and no path file written.
printf 'boundary 0 0 0 10 10 10\nblock 4.99 0 0 5.01 10 10\n' >"$tmp/sealed.txt"
for algo in astar thetastar visgraph; do
  "$BIN" map3d --map "$tmp/sealed.txt" --start 1,5,5 --goal 9,5,5 --algo "$algo" --json \
    --path-out "$tmp/none.csv" >"$tmp/o" 2>"$tmp/e" || fail "unreachable goal ($algo): exit $?"
  "$PY" -c "import json; j=json.load(open('$tmp/o')); assert j['status']=='no_path' and j['path']==[], j" ||
    fail "unreachable goal ($algo): $(cat "$tmp/o")"
  grep -q "found no path (no_path)" "$tmp/e" || fail "unreachable goal message: $(cat "$tmp/e")"
  [[ ! -e "$tmp/none.csv" ]] || fail "a path file was written for an unsolved query"
done
"$BIN" map3d --map "$tmp/sealed.txt" --start 1,5,5 --goal 9,5,5 --algo rrt --time 0.2 >"$tmp/o" 2>"$tmp/e" ||
  fail "rrt timeout: exit $?"
grep -q "status *timeout" "$tmp/o" && grep -q "(timeout); raise --time" "$tmp/e" || fail "rrt timeout: $(cat "$tmp/o" "$tmp/e")"
# A memory budget is an answer too.
"$BIN" map3d --map "$MAPS/maze.txt" --max-states 1000 --json >"$tmp/o" 2>"$tmp/e" || fail "budget: exit $?"
"$PY" -c "import json,sys; assert json.load(open(sys.argv[1]))['status']=='budget_exceeded'" "$tmp/o" ||
  fail "budget: $(cat "$tmp/o" "$tmp/e")"

# Files that are not world files: a device that never ends, one endless line.
expect_bad "larger than 64 MiB" map3d --map /dev/zero --start 1,1,1 --goal 2,2,2
head -c 10000 /dev/zero | tr '\0' 'x' >"$tmp/long.txt"
expect_bad "long.txt:1: line longer than 4096 bytes" map3d --map "$tmp/long.txt" --start 1,1,1 --goal 2,2,2
expect_bad "larger than 64 MiB" sphere2d --map /dev/zero --start 1,1 --goal 2,2

# --shortcut keeps the exact ends when the goal lies on the boundary's face (z = 0.1 is not
# 4.9 + (0.1 - 4.9) in doubles): every planner that tightens.
printf 'boundary 0 0 0 4.3 20 5\nblock 1.0 0 0 1.1 19 5\nblock 2.1 1 0 2.2 20 5\n' >"$tmp/edge.txt"
for algo in visgraph astar birrt thetastar; do
  "$BIN" map3d --map "$tmp/edge.txt" --start 0.5,1.0,4.9 --goal 3.0,1.0,0.1 --algo "$algo" --time 60 \
    --shortcut --json >"$tmp/o" 2>"$tmp/e" || fail "edge map $algo --shortcut: $(cat "$tmp/e")"
  "$PY" -c "import json; j=json.load(open('$tmp/o')); assert j['status']=='solved' and j['path'][-1]==[3.0,1.0,0.1], j['path'][-1]" ||
    fail "edge map $algo: bad end"
done
echo "world cli: all checks passed"
