#!/usr/bin/env bash
# hpcplan sim end to end: the JSON summary, the per-run CSV (seed 000's 14 columns first), the
# per-replan log, byte-identical lockstep runs, VTK with the robot read back by VTK's readers,
# a realtime run, restart from a checkpoint, bad input (one line, exit 2, nothing written).
set -uo pipefail
bin=$1
py=/usr/bin/python3
[[ -x $py ]] || py=python3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "sim_cli: FAIL: $*" >&2; exit 1; }

base=(--particles 1000 --scenario dynamic --seed 3 --settle-frames 40 --max-sim-s 12)
common1=("${base[@]}" --threads 2)
common=("${common1[@]}" --runs 2)
for k in 1 2; do
  "$bin" sim "${common[@]}" --algo rrtstar --csv "$dir/runs$k.csv" --replan-log "$dir/replans$k.csv" \
    --trajectory "$dir/traj$k.csv" --no-timings --json --output "$dir/out$k.json" > "$dir/stdout$k.json" ||
    fail "lockstep run $k failed"
done
cmp -s "$dir/stdout1.json" "$dir/out1.json" || fail "--output differs from stdout"
for f in runs replans traj; do
  cmp -s "$dir/${f}1.csv" "$dir/${f}2.csv" || fail "lockstep $f.csv differs between identical runs"
done
python3 - "$dir" <<'PY' || exit 1
import csv, json, sys
d = sys.argv[1]
j = json.load(open(f"{d}/out1.json"))
for k in ["scenario", "algorithm", "particles", "pace", "seed", "threads", "runs", "aggregate"]:
    assert k in j, k
assert j["algorithm"] == "rrtstar" and j["pace"] == "lockstep" and len(j["runs"]) == 2, j
a = j["aggregate"]
for k in ["success_rate", "failed_replan_rate", "plan_time_us_p50", "plan_time_us_p99",
          "total_replans", "sph_ms_per_frame_median"]:
    assert k in a, k
rows = list(csv.reader(open(f"{d}/runs1.csv")))
seed = ["scenario", "algorithm", "run_number", "success", "time_to_goal_s", "total_replans",
        "failed_replans", "avg_plan_time_us", "min_plan_time_us", "max_plan_time_us",
        "avg_path_length", "avg_path_nodes", "avg_path_divergence", "particle_count"]
assert rows[0][:14] == seed, rows[0][:14]
# The safety columns come right after the seed's 14 (sim/safety.hpp).
assert rows[0][14:19] == ["contacts", "contact_frames", "contact_time_s", "min_clearance",
                          "max_overlap"], rows[0][14:19]
assert len(rows) == 3, len(rows)
h = rows[0]
for r in rows[1:]:
    row = dict(zip(h, r))
    assert row["scenario"] == "dynamic" and row["particle_count"] == "1000", row
    assert int(row["total_replans"]) >= int(row["failed_replans"]) >= 0, row
    assert row["avg_plan_time_us"] == "", "--no-timings leaves timings empty"
    assert row["pace"] == "lockstep" and row["seed"] == "3", row
    assert row["end"] in ("goal_reached", "sim_time_cap"), row
    assert (row["end"] == "goal_reached") == (row["success"] == "1"), row
    assert row["controller"] == "seed", row
    assert int(row["contact_frames"]) >= int(row["contacts"]) >= 0, row
    assert abs(float(row["contact_time_s"]) - 0.02 * int(row["contact_frames"])) < 1e-6, row
    assert float(row["max_overlap"]) == max(0.0, -float(row["min_clearance"])), row
# The trajectory's clearance column agrees with the per-run figures.
traj = list(csv.DictReader(open(f"{d}/traj1.csv")))
assert "clearance" in traj[0], traj[0].keys()
for r in rows[1:]:
    row = dict(zip(h, r))
    c = [float(t["clearance"]) for t in traj if t["run"] == row["run_number"]]
    assert len(c) == int(row["frames"]), (len(c), row["frames"])
    assert sum(x < 0 for x in c) == int(row["contact_frames"]), row
    assert abs(min(c) - float(row["min_clearance"])) <= 1e-6 * max(1, abs(min(c))), row
    events = sum(1 for i, x in enumerate(c) if x < 0 and (i == 0 or c[i - 1] >= 0))
    assert events == int(row["contacts"]), (events, row)
for r in j["runs"]:
    s = r["safety"]
    assert set(s) >= {"contacts", "contact_frames", "contact_time_s", "contact_rate",
                      "min_clearance", "max_overlap"}, s
for k in ["contact_rate_mean", "contact_rate_p50", "contact_rate_p95", "contact_rate_max",
          "contact_rate_all_frames"]:
    assert k in a, k
assert j["controller"] == "seed" and j["robot_radius"] == 0.05, j
assert j["occupancy"] == {"rule": "particles", "cell": 0.2, "particle_radius": 0.14}, j
assert all(r["occupancy"] == "particles" for r in csv.DictReader(open(f"{d}/runs1.csv"))), d
rep = list(csv.reader(open(f"{d}/replans1.csv")))
assert rep[0][:11] == ["run", "frame", "sim_time_s", "algorithm", "status", "reason", "plan_us",
                       "expanded", "length", "waypoints", "divergence"], rep[0]
total = sum(int(dict(zip(h, r))["total_replans"]) for r in rows[1:])
assert len([r for r in rep[1:] if r[5] != "cancelled"]) == total, (len(rep), total)
for r in rep[1:]:
    # status in the shared Status vocabulary; reason the seed's failure category it implies
    reasons = {"solved": {""}, "no_path": {"start_blocked", "goal_blocked", "disconnected"},
               "budget_exceeded": {"budget"}, "timeout": {"budget"}, "cancelled": {"cancelled"}}
    assert r[4] in reasons and r[5] in reasons[r[4]], r
print("sim_cli: lockstep, json and csv ok")
PY

# The reactive layer: same scene, fewer frames in contact (none on this one), the goal reached.
"$bin" sim "${common[@]}" --algo rrtstar --controller reactive --no-timings \
  --csv "$dir/reactive.csv" > /dev/null || fail "reactive run failed"
python3 - "$dir/runs1.csv" "$dir/reactive.csv" <<'PY' || exit 1
import csv, sys
plain = list(csv.DictReader(open(sys.argv[1])))
react = list(csv.DictReader(open(sys.argv[2])))
assert all(r["controller"] == "reactive" and r["success"] == "1" for r in react), react
p = sum(int(r["contact_frames"]) for r in plain)
q = sum(int(r["contact_frames"]) for r in react)
assert q <= p and int(react[0]["reactive_overrides"]) > 0, (p, q)
print(f"sim_cli: reactive ok (frames in contact {p} -> {q})")
PY

# dambreak: the water column (250 particles round to 432), no settling, the run and its JSON.
"$bin" sim --particles 250 --scenario dambreak --algo astar --max-sim-s 0.4 --json \
  > "$dir/dam.json" || fail "dambreak run failed"
"$py" - "$dir/dam.json" <<'PY' || exit 1
import json, sys
j = json.load(open(sys.argv[1]))
assert j["scenario"] == "dambreak" and j["settle_frames"] == 0, j
row = j["runs"][0]
assert row["particle_count"] == 432 and row["end"] in ("goal_reached", "sim_time_cap"), row
assert row["total_replans"] >= 2, row
print("sim_cli: dambreak ok")
PY

# VTK with the robot: read back by VTK's own readers.
"$bin" sim --particles 600 --scenario static --algo astar --max-sim-s 2 --settle-frames 5 \
  --vtk "$dir/vtk" --every 20 > /dev/null || fail "vtk run failed"
"$py" - "$dir/vtk/run_1" <<'PY' || exit 1
import os, sys, xml.etree.ElementTree as ET
import vtk
from vtk.util.numpy_support import vtk_to_numpy
d = sys.argv[1]
sets = ET.parse(os.path.join(d, "fluid.pvd")).getroot().find("Collection").findall("DataSet")
robots = [s.get("file") for s in sets if s.get("part") == "2"]
assert robots and robots[0] == "robot_000020.vtu", robots
for name in robots:
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(os.path.join(d, name))
    r.Update()
    g = r.GetOutput()
    roles = list(vtk_to_numpy(g.GetCellData().GetArray("role")))
    assert roles[:2] == [0, 1], roles          # robot, goal
    types = [g.GetCellType(i) for i in range(g.GetNumberOfCells())]
    assert types[:2] == [1, 1] and all(t == 4 for t in types[2:]), types
    assert 3 in roles, "the trail is a polyline"
print("sim_cli: vtk ok")
PY
# The headless render draws the robot's part too.
"$py" "$(dirname "$0")/../../scripts/render_sph.py" "$dir/vtk/run_1" --out "$dir/render" \
  > /dev/null || fail "render_sph.py failed on a simulator run"
[[ $(ls "$dir"/render_*.png | wc -l) -ge 2 && ( -s $dir/render.mp4 || -s $dir/render.gif ) ]] ||
  fail "render: frames or animation missing"
echo "sim_cli: render ok"

# Realtime: frames are paced to 0.02 s of wall time, from both sides: no faster, and not falling
# behind realtime. That side is a guard, 10 times what pacing makes the run (each frame its
# 0.02 s or its fluid step, whichever is longer: a loaded machine's steps can be longer). One
# thread: OpenMP's threads beside a busy process made a 500-particle step take 150 ms, not 0.2.
"$bin" sim --particles 500 --algo astar --pace realtime --max-sim-s 1 --settle-frames 0 --threads 1 \
  --json > "$dir/rt.json" || fail "realtime run failed"
python3 - "$dir/rt.json" <<'PY' || exit 1
import json, sys
j = json.load(open(sys.argv[1]))
assert j["pace"] == "realtime", j
r = j["runs"][0]
assert r["wall_time_s"] >= 0.95 * r["time_to_goal_s"], r
paced = r["frames"] * max(r["time_to_goal_s"] / r["frames"], r["sph_ms_per_frame"] / 1e3)
assert r["wall_time_s"] <= 10 * paced, (r["wall_time_s"], paced, r)
print("sim_cli: realtime ok")
PY

# Adaptive occupancy: the run says which rule its grid used, in the JSON and in each CSV row. In
# the scenario without boxes, a threshold above any density the fluid reaches blocks no cell: every
# replan is solved as the straight segment (2 waypoints), no end ever escapes; the seed's rule on
# the same scene blocks cells (escapes, bent paths), so a rule that were ignored would fail here.
occ=(--particles 1000 --scenario particles --runs 2 --seed 3 --threads 2 --settle-frames 40
     --max-sim-s 12 --algo astar --no-timings)
"$bin" sim "${occ[@]}" --occupancy density --density-threshold 1e6 --csv "$dir/density.csv" \
  --replan-log "$dir/density_replans.csv" --output "$dir/density.json" > /dev/null ||
  fail "density occupancy run failed"
"$bin" sim "${occ[@]}" --replan-log "$dir/seedrule_replans.csv" > /dev/null ||
  fail "seed-occupancy run failed"
python3 - "$dir/density.csv" "$dir/density.json" "$dir/density_replans.csv" \
  "$dir/seedrule_replans.csv" <<'PY' || exit 1
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
j = json.load(open(sys.argv[2]))
assert j["occupancy"] == {"rule": "density", "cell": 0.2, "density_support": 0.28,
                          "density_threshold": 1e6}, j["occupancy"]
assert rows and all(r["occupancy"] == "density:0.28:1e+06" for r in rows), rows
dens = list(csv.DictReader(open(sys.argv[3])))
seed = list(csv.DictReader(open(sys.argv[4])))
assert dens and all(r["status"] == "solved" and r["waypoints"] == "2" and
                    r["start_escaped"] == r["goal_escaped"] == "0" for r in dens), dens
assert any(r["start_escaped"] == "1" or r["goal_escaped"] == "1" for r in seed), seed
assert any(int(r["waypoints"]) > 2 for r in seed if r["status"] == "solved"), seed
print("sim_cli: density occupancy ok")
PY

# Restart: run 1 made and checkpointed by one invocation, run 2 by another restarted from its
# checkpoint; together they write the uninterrupted invocation's CSVs byte for byte (lockstep,
# --no-timings) and its JSON figures.
"$bin" sim "${common1[@]}" --runs 1 --algo rrtstar --trajectory "$dir/traj_a.csv" \
  --checkpoint "$dir/sim.ck" > /dev/null 2>&1 || fail "restart: the first part failed"
# (The restart runs on one thread: no result depends on the thread count.)
"$bin" sim "${base[@]}" --runs 2 --algo rrtstar --threads 1 --restart "$dir/sim.ck" --checkpoint "$dir/sim.ck" \
  --csv "$dir/runs_r.csv" --replan-log "$dir/replans_r.csv" --trajectory "$dir/traj_r.csv" \
  --no-timings --json > "$dir/restart.json" 2> /dev/null || fail "restart: the restart failed"
for f in runs replans traj; do
  cmp -s "$dir/${f}1.csv" "$dir/${f}_r.csv" || fail "restart: $f.csv differs from the uninterrupted run's"
done
python3 - "$dir/out1.json" "$dir/restart.json" <<'PY' || fail "restart: JSON figures differ"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
timed = {"wall_time_s", "plan_time_us", "sph_ms_per_frame", "snapshot_ms", "seconds", "threads"}
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if k not in timed and not k.startswith(("plan_time_us", "sph_ms"))}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
assert strip(a) == strip(b), (strip(a), strip(b))
PY
# Every run already made: the new checkpoint is still written, naming them all.
"$bin" sim "${common[@]}" --algo rrtstar --trajectory "$dir/traj_d.csv" --restart "$dir/sim.ck" \
  --checkpoint "$dir/done.ck" > /dev/null 2>&1 || fail "restart: a finished checkpoint's restart failed"
[[ -s $dir/done.ck ]] || fail "restart: nothing left to run wrote no checkpoint"
cmp -s "$dir/traj1.csv" "$dir/traj_d.csv" || fail "restart: the finished checkpoint's trajectory differs"
echo "sim_cli: restart ok"

# Interrupted by SLURM's warning signal once run 1 is saved: the invocation ends after the
# current frame (exit 0, status interrupted), the run under way is dropped whole, and a restart
# makes the rest: together the uninterrupted invocation's CSVs, byte for byte.
"$bin" sim "${common1[@]}" --runs 3 --algo rrtstar --csv "$dir/runs3.csv" --trajectory "$dir/traj3.csv" \
  --no-timings > /dev/null 2>&1 || fail "interrupt: the reference failed"
rm -f "$dir/int.ck"
"$bin" sim "${common1[@]}" --runs 3 --algo rrtstar --trajectory "$dir/traj_i.csv" \
  --checkpoint "$dir/int.ck" --no-timings --json > "$dir/int.json" 2> /dev/null &
pid=$!
# The signal goes once run 1 is saved, whenever that is (under AddressSanitizer the first run
# takes longer): the wait fails if the invocation ends first, and after 300 s (a guard). Runs 2
# and 3 still take seconds (a machine 10 times faster: half a second) when it goes.
deadline=$((SECONDS + 300))
until [[ -e $dir/int.ck ]]; do
  kill -0 "$pid" 2> /dev/null || fail "interrupt: the invocation ended before its first run was saved"
  ((SECONDS < deadline)) || { kill "$pid"; fail "interrupt: run 1 not saved within 300 s"; }
  sleep 0.01
done
kill -USR1 "$pid"
wait "$pid" || fail "interrupt: exit $?"
python3 - "$dir/int.json" <<'PY' || fail "interrupt: report"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["status"] == "interrupted" and j["interrupted_by"] == "SIGUSR1", j
assert 1 <= len(j["runs"]) < 3, len(j["runs"])
PY
"$bin" sim "${common1[@]}" --runs 3 --algo rrtstar --trajectory "$dir/traj_i.csv" \
  --restart "$dir/int.ck" --csv "$dir/runs_i.csv" --no-timings > /dev/null 2>&1 ||
  fail "interrupt: the restart failed"
cmp -s "$dir/runs3.csv" "$dir/runs_i.csv" || fail "interrupt: the runs differ from the uninterrupted ones"
cmp -s "$dir/traj3.csv" "$dir/traj_i.csv" || fail "interrupt: the trajectory differs"
echo "sim_cli: interrupt ok"

# The wall-time cap: a cap no frame can meet ends every run after its first frame, recorded as
# failed (wall_time_cap), never dropped.
"$bin" sim --particles 300 --settle-frames 0 --runs 2 --max-wall-s 1e-9 --csv "$dir/wall.csv" \
  > /dev/null 2>&1 || fail "wall-time cap: the run failed"
python3 - "$dir/wall.csv" <<'PY' || fail "wall-time cap: rows"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, rows
for r in rows:
    assert r["end"] == "wall_time_cap" and r["success"] == "0" and r["frames"] == "1", r
PY
echo "sim_cli: wall-time cap ok"

# Bad input: one line on stderr, exit 2, no file written.
bad() {
  local expect=$1; shift
  rm -f "$dir/bad.csv"
  "$bin" sim "$@" --csv "$dir/bad.csv" > /dev/null 2> "$dir/err"
  local rc=$?
  [[ $rc -eq 2 ]] || fail "'$*' exited $rc, not 2"
  [[ $(wc -l < "$dir/err") -eq 1 ]] || fail "'$*' printed more than one line: $(cat "$dir/err")"
  grep -q -- "$expect" "$dir/err" || fail "'$*' did not mention '$expect': $(cat "$dir/err")"
  [[ ! -e $dir/bad.csv ]] || fail "'$*' wrote its CSV"
}
bad "particles" --particles 1
bad "scenario" --scenario tank
bad "scenario" --scenario nosuch
bad "backend" --backend gpu
if ! "$bin" sim --backend cuda --particles 300 --max-sim-s 0.1 --settle-frames 0 > /dev/null 2>&1; then
  bad "backend cuda" --backend cuda
fi
bad "planner" --algo nosuch
bad "pace" --pace fast
bad "controller" --controller fast
bad "occupancy" --occupancy fluid
bad "density-threshold" --occupancy density --density-threshold 0
bad "density-support" --occupancy density --density-support -1
bad "need --occupancy density" --density-threshold 2
bad "applies to the grid planners" --occupancy density --algo rrtstar
bad "robot-radius" --robot-radius -1
bad "reactive-horizon" --reactive-horizon 0
bad "replan-every" --replan-every 0
bad "max-sim-s" --max-sim-s 0
bad "max-wall-s" --max-wall-s -1
bad "goal-bias" --goal-bias 2
bad "memory" --particles 100000000 --memory-mb 16
bad "vtk" --vtk "$dir/bad.csv/x"
bad "other options" "${common[@]}" --algo rrtstar --replan-every 5 --trajectory "$dir/t.csv" --restart "$dir/sim.ck"
bad "other options" "${common[@]}" --algo rrtstar --lockstep-delay 5 --trajectory "$dir/t.csv" --restart "$dir/sim.ck"
bad "past --runs 1" "${common1[@]}" --runs 1 --algo rrtstar --trajectory "$dir/t.csv" --restart "$dir/sim.ck"
head -c 100 "$dir/sim.ck" > "$dir/sim_cut.ck"
bad "cut short" "${common[@]}" --algo rrtstar --trajectory "$dir/t.csv" --restart "$dir/sim_cut.ck"
cp "$dir/sim.ck" "$dir/sim_flip.ck"
printf '\x7f' | dd of="$dir/sim_flip.ck" bs=1 seek=300 conv=notrunc 2> /dev/null
bad "checksum" "${common[@]}" --algo rrtstar --trajectory "$dir/t.csv" --restart "$dir/sim_flip.ck"
# A checkpoint sealed with a sound checksum around a payload nested 150,000 deep (the CBOR
# reader recurses: read naively, it exhausts the stack).
python3 - "$dir/sim.ck" "$dir/deep.ck" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
magic = b"hpcplan simulator checkpoint\n"
n = struct.unpack_from("<Q", data, len(magic) + 4)[0]
head = data[:len(magic) + 4 + 8 + n]
payload = b"\x81" * 150000 + b"\x00"
h = 0xcbf29ce484222325
for b in payload:
    h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
open(sys.argv[2], "wb").write(head + struct.pack("<Q", len(payload)) + payload + struct.pack("<Q", h))
PY
bad "cannot read" "${common[@]}" --algo rrtstar --trajectory "$dir/t.csv" --restart "$dir/deep.ck"
bad "other options" "${common[@]}" --algo rrtstar --restart "$dir/sim.ck"  # no --trajectory now
printf 'hpcplan fluid checkpoint\n' > "$dir/fluid.ck"
bad "not an hpcplan simulator checkpoint" --restart "$dir/fluid.ck"
bad "not a readable regular file" --restart /dev/zero
bad "an empty path" --checkpoint ""
bad "also another output" --checkpoint "$dir/bad.csv"
rm -f "$dir/bad.csv"
"$bin" sim --particles 500 --replan-log /nonexistent/dir/log.csv > /dev/null 2> "$dir/err"
[[ $? -eq 2 ]] || fail "unwritable --replan-log is not exit 2"
echo "sim_cli: all ok"
