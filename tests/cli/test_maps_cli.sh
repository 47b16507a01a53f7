#!/usr/bin/env bash
# hpcplan grid --map and hpcplan scen from the command line: answers in the report, and every
# bad file or option refused in one line with exit 2 (nothing written), a wrong published
# length a failed run (exit 1), before or after any search as the case requires.
# Usage: bash tests/cli/test_maps_cli.sh path/to/hpcplan MOVINGAI_DIR
set -uo pipefail
bin=$1
dir=$2
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

# expect CODE WORD ARGS...: exit CODE, and for exit 2 one line on stderr containing WORD.
expect() {
  local code=$1 word=$2
  shift 2
  local rc=0
  timeout 120 "$bin" "$@" >"$tmp/out" 2>"$tmp/err" || rc=$?
  if ((rc != code)); then
    echo "test_maps_cli: FAIL (exit $rc, not $code): hpcplan $* :: $(head -c 300 "$tmp/err")" >&2
    fail=1
    return
  fi
  if [[ -n $word ]]; then
    if [[ $(wc -l <"$tmp/err") -ne 1 ]] || ! grep -qF -- "$word" "$tmp/err"; then
      echo "test_maps_cli: FAIL (not one line naming '$word'): hpcplan $* :: $(cat "$tmp/err")" >&2
      fail=1
    fi
  fi
}

m=$dir/Boston_0_256.map
# Answers: the report names the map, its shape and the format's connectivity.
"$bin" grid --map "$m" --start 188,1 --goal 12,231 --json >"$tmp/a.json" || fail=1
"$py" - "$tmp/a.json" <<'PY' || fail=1
import json, sys
j = json.load(open(sys.argv[1]))
ok = (j["status"] == "solved" and abs(j["cost"] - 378.88434295) < 1e-6 and j["obstacles"] == "movingai"
      and j["map"] == "Boston_0_256.map" and j["shape"] == [256, 256] and j["connectivity"] == "seed"
      and j["pruning"] == "jump_points" and "seed" not in j)
if not ok:
    print("test_maps_cli: FAIL grid --map report:", j, file=sys.stderr)
sys.exit(0 if ok else 1)
PY

# Bad map files.
printf 'type octile\nheight 2\nwidth 3\nmap\n...\n..\n' >"$tmp/short.map"
printf 'type octile\nheight 2\nwidth 3\nmaq\n...\n...\n' >"$tmp/header.map"
printf 'type octile\nheight 2\nwidth 3\nmap\n..X\n...\n' >"$tmp/char.map"
printf 'voxel 4 4 4\n1 2 3\n4 0 0\n' >"$tmp/range.3dmap"
printf 'type octile\nheight 2\nwidth 3\nmap\n@..\n...\n' >"$tmp/ok.map"
"$py" - "$tmp/huge.npy" <<'PY'
import sys
d = "{'descr': '|u1', 'fortran_order': False, 'shape': (100000, 100000), }"
h = d + " " * (118 - len(d)) + "\n"
open(sys.argv[1], "wb").write(b"\x93NUMPY\x01\x00" + len(h).to_bytes(2, "little") + h.encode() + b"\0" * 1000)
PY
printf 'x' >"$tmp/map.txt"
expect 2 "short.map" grid --map "$tmp/short.map" --start 0,0 --goal 2,1
expect 2 "header.map" grid --map "$tmp/header.map" --start 0,0 --goal 2,1
expect 2 "char.map" grid --map "$tmp/char.map" --start 0,0 --goal 2,1
expect 2 "range.3dmap" grid --map "$tmp/range.3dmap" --start 0,0,0 --goal 1,1,1
expect 2 "huge.npy" grid --map "$tmp/huge.npy" --start 0,0 --goal 1,1
expect 2 ".map, .3dmap or .npy" grid --map "$tmp/map.txt" --start 0,0 --goal 1,1
expect 2 "inside an obstacle" grid --map "$tmp/ok.map" --start 0,0 --goal 2,1
expect 2 "outside the map [0, 2] x [0, 1]" grid --map "$tmp/ok.map" --start 1,0 --goal 3,1
expect 2 "the map has 2 dimensions" grid --map "$tmp/ok.map" --start 1,0,0 --goal 2,1
expect 2 "--seed describes the GOG field" grid --map "$tmp/ok.map" --start 1,0 --goal 2,1 --seed 3
expect 2 "--dims 3 but" grid --map "$tmp/ok.map" --dims 3 --start 1,0 --goal 2,1
expect 2 "--dims is required" grid --start 1,0 --goal 2,1
expect 0 "" grid --map "$tmp/ok.map" --start 1,0 --goal 2,1

# Scenarios.
s=$dir/Boston_0_256.map.scen
expect 0 "" scen "$s" --buckets 3-4 --csv "$tmp/rows.csv" --output "$tmp/sum.json"
"$py" - "$tmp/rows.csv" "$tmp/sum.json" "$s" <<'PY' || fail=1
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
j = json.load(open(sys.argv[2]))
published = [l.split("\t") for l in open(sys.argv[3]).read().splitlines()[1:] if l.strip()]
want = [i for i, r in enumerate(published) if 3 <= int(r[0]) <= 4]
ok = [int(r["row"]) for r in rows] == want and j["rows"] == len(want) == 20
ok = ok and j["mismatches"] == 0 and all(r["status"] == "solved" and r["mismatch"] == "0" for r in rows)
ok = ok and all(abs(float(r["cost"]) - float(published[int(r["row"])][8])) < 1e-6 for r in rows)
ok = ok and [b["bucket"] for b in j["buckets"]] == [3, 4] and j["buckets"][0]["rows"] == 10
if not ok:
    print("test_maps_cli: FAIL scen --csv/--output", j, rows[:2], file=sys.stderr)
sys.exit(0 if ok else 1)
PY
expect 2 "--buckets" scen "$s" --buckets 5-x
expect 2 "no scenario rows" scen "$s" --buckets 900-901
cp "$s" "$tmp/alone.map.scen"
expect 2 "not beside it" scen "$tmp/alone.map.scen"
expect 2 "the map '64room_005.map' is 512 x 512" scen "$s" --map "$dir/64room_005.map"
# A wrong published length: exit 1, the summary printed, the row named.
{ head -1 "$s"; sed -n 2p "$s" | awk -F'\t' 'BEGIN{OFS="\t"} {$9="1.0"; print}'; sed -n 3p "$s"; } \
  >"$tmp/wrong.map.scen"
cp "$m" "$tmp/Boston_0_256.map"
expect 1 "" scen "$tmp/wrong.map.scen" --csv "$tmp/wrong.csv"
grep -q "1 of 2 rows differ from the published optimum (first: row 0)" "$tmp/err" ||
  { echo "test_maps_cli: FAIL mismatch message: $(cat "$tmp/err")" >&2; fail=1; }
grep -q "1 mismatches" "$tmp/out" || { echo "test_maps_cli: FAIL mismatch summary" >&2; fail=1; }
[[ $(sed -n 2p "$tmp/wrong.csv" | awk -F, '{print $NF}') == 1 ]] ||
  { echo "test_maps_cli: FAIL mismatch not flagged in --csv" >&2; fail=1; }

# A voxel scenario (.3dmap + .3dscen, 26-connected without corner cutting): no public file is
# in reach here, so this script writes one with its own Dijkstra's lengths; every engine must
# answer each row with them.
"$py" - "$tmp" <<'PY' || fail=1
import heapq, itertools, math, random, sys
t = sys.argv[1]
random.seed(9)
W, H, D = 12, 10, 8
blocked = {(x, y, z) for x in range(W) for y in range(H) for z in range(D) if random.random() < 0.3}
def free(c):
    return all(0 <= v < n for v, n in zip(c, (W, H, D))) and c not in blocked
moves = [m for m in itertools.product((-1, 0, 1), repeat=3) if any(m)]
def dijkstra(s, g):
    dist = {s: 0.0}
    heap = [(0.0, s)]
    while heap:
        d, c = heapq.heappop(heap)
        if c == g:
            return d
        if d > dist[c]:
            continue
        for m in moves:
            axes = [i for i in range(3) if m[i]]
            ok = all(free(tuple(c[i] + (m[i] if i in sub else 0) for i in range(3)))
                     for k in range(1, len(axes) + 1) for sub in itertools.combinations(axes, k))
            if not ok:
                continue
            n = tuple(c[i] + m[i] for i in range(3))
            nd = d + math.sqrt(len(axes))
            if nd < dist.get(n, math.inf):
                dist[n] = nd
                heapq.heappush(heap, (nd, n))
    return None
cells = [c for c in itertools.product(range(W), range(H), range(D)) if free(c)]
rows = []
while len(rows) < 12:
    s, g = random.choice(cells), random.choice(cells)
    d = dijkstra(s, g)
    if d is not None:
        rows.append((s, g, d))
with open(f"{t}/v.3dmap", "w") as f:
    f.write(f"voxel {W} {H} {D}\n" + "".join(f"{x} {y} {z}\n" for x, y, z in sorted(blocked)))
with open(f"{t}/v.3dmap.3dscen", "w") as f:
    f.write("version 1\nv.3dmap\n")
    for s, g, d in rows:
        f.write(f"{s[0]} {s[1]} {s[2]} {g[0]} {g[1]} {g[2]} {d:.8f} 1.0\n")
PY
for run in "--algo astar" "--algo dijkstra --engine dense" "--algo dijkstra --engine sparse"; do
  # shellcheck disable=SC2086
  expect 0 "" scen "$tmp/v.3dmap.3dscen" $run --json
  grep -q '"rows":12,' "$tmp/out" && grep -q '"mismatches":0,' "$tmp/out" && grep -q '"connectivity":"full"' "$tmp/out" ||
    { echo "test_maps_cli: FAIL .3dscen $run: $(cat "$tmp/out")" >&2; fail=1; }
done

# Auto takes the sparse engine where the dense one's hypercube of padded tiles would dwarf the
# array (a 1 x 65535 line planned 5.9 GB dense), the dense one on a 2D map.
"$py" -c "import numpy as np; np.save('$tmp/line.npy', np.zeros((1, 65535), np.uint8))"
expect 0 "" grid --map "$tmp/line.npy" --algo bfs --start 0,0 --goal 65534,0 --json
grep -q '"engine":"sparse"' "$tmp/out" && grep -q '"hops":65534' "$tmp/out" ||
  { echo "test_maps_cli: FAIL the line array: $(head -c 300 "$tmp/out")" >&2; fail=1; }
expect 0 "" grid --map "$m" --start 188,1 --goal 12,231 --algo dijkstra --json
grep -q '"engine":"dense"' "$tmp/out" || { echo "test_maps_cli: FAIL Boston not dense" >&2; fail=1; }
# Every row is checked before any runs: a row of another map, a blocked end.
{ head -2 "$s"; sed -n 3p "$s" | awk -F'\t' 'BEGIN{OFS="\t"} {$2="Other.map"; print}'; } >"$tmp/two.map.scen"
cp "$m" "$tmp/two.map"
expect 2 "names the map 'Other.map'" scen "$tmp/two.map.scen" --map "$m"
{ head -2 "$s"; sed -n 3p "$s" | awk -F'\t' 'BEGIN{OFS="\t"} {$5="21"; $6="0"; print}'; } >"$tmp/blocked.map.scen"
expect 2 "scenario row 1: its start is blocked" scen "$tmp/blocked.map.scen" --map "$m"

# Checkpoints on a map: a restart continues on the same map and is refused on an edited one.
expect 0 "" grid --map "$m" --start 188,1 --goal 12,231 --algo bfs --engine dense \
  --checkpoint "$tmp/ck" --checkpoint-every 0.0001
[[ -s $tmp/ck ]] || { echo "test_maps_cli: FAIL no checkpoint written" >&2; fail=1; }
expect 0 "" grid --map "$m" --start 188,1 --goal 12,231 --algo bfs --engine dense --restart "$tmp/ck" --json
grep -q '"restarted_from"' "$tmp/out" || { echo "test_maps_cli: FAIL restart not reported" >&2; fail=1; }
sed '10s/\./@/' "$m" >"$tmp/edited.map"
expect 2 "occupancy checksum" grid --map "$tmp/edited.map" --start 188,1 --goal 12,231 --algo bfs \
  --engine dense --restart "$tmp/ck"

((fail == 0)) && echo "test_maps_cli: every case as expected"
exit "$fail"
