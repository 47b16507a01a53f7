#!/usr/bin/env bash
# hpcplan sph end to end: the JSON report, VTK output read back by VTK's own XML readers
# (Debian's python3-vtk9, as ParaView reads it), the dam break's front CSV, SPHERIC Test 2's
# gauges, checkpoint and restart, bad input.
set -uo pipefail
bin=$1
# Debian's interpreter, which has python3-vtk9 (a python3 earlier in PATH may not).
py=/usr/bin/python3
[[ -x $py ]] || py=python3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "sph_cli: FAIL: $*" >&2; exit 1; }

"$bin" sph --preset seed --scenario dynamic --particles 800 --frames 12 --seed 4 --threads 2 \
  --vtk "$dir/vtk" --every 5 --json --output "$dir/run.json" > "$dir/out.json" ||
  fail "seed run failed"
cmp -s "$dir/out.json" "$dir/run.json" || fail "--output differs from stdout"
python3 - "$dir/out.json" <<'PY' || exit 1
import json, sys
j = json.load(open(sys.argv[1]))
keys = ["status", "preset", "scenario", "particles", "frames", "substeps", "box",
        "ms_per_frame_median", "ms_per_frame_max", "particle_steps_per_s", "neighbours_mean",
        "neighbours_max", "max_density_error", "kinetic_energy", "threads", "seed", "backend"]
missing = [k for k in keys if k not in j]
assert not missing, f"missing keys {missing}"
assert j["status"] == "ok" and j["preset"] == "seed" and j["scenario"] == "dynamic", j
assert j["particles"] == 800 and j["frames"] == 12 and j["threads"] == 2 and j["seed"] == 4, j
assert j["substeps"] >= 12 and j["backend"] == "cpu", j
assert j["particle_steps_per_s"] > 0 and j["kinetic_energy"] > 0, j
L = 5 * (800 / 1500) ** (1 / 3)
assert abs(j["box"][1][0] - L) < 1e-9, j["box"]
print("sph_cli: json ok")
PY

# VTK: frames 0, 5, 10 and the last (12); each read back by VTK's readers.
"$py" - "$dir/vtk" <<'PY' || exit 1
import os, sys, xml.etree.ElementTree as ET
import vtk
from vtk.util.numpy_support import vtk_to_numpy
d = sys.argv[1]
pvd = ET.parse(os.path.join(d, "fluid.pvd")).getroot()
sets = pvd.find("Collection").findall("DataSet")
files = [s.get("file") for s in sets]
assert files == ["fluid_000000.vtu", "boxes_000000.vtu", "fluid_000005.vtu", "boxes_000005.vtu",
                 "fluid_000010.vtu", "boxes_000010.vtu", "fluid_000012.vtu", "boxes_000012.vtu"], files
times = [float(s.get("timestep")) for s in sets[::2]]
assert all(abs(t - e) < 1e-9 for t, e in zip(times, [0.0, 0.1, 0.2, 0.24])), times
for name in files:
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(os.path.join(d, name))
    r.Update()
    g = r.GetOutput()
    if name.startswith("fluid"):
        assert g.GetNumberOfPoints() == 800 and g.GetNumberOfCells() == 800, name
        pd = g.GetPointData()
        for a, comps in (("velocity", 3), ("density", 1), ("pressure", 1), ("id", 1)):
            arr = pd.GetArray(a)
            assert arr is not None and arr.GetNumberOfComponents() == comps, (name, a)
        pts = vtk_to_numpy(g.GetPoints().GetData())
        L = 5 * (800 / 1500) ** (1 / 3)
        assert pts.min() >= 0 and pts.max() <= L, (name, pts.min(), pts.max())
        rho = vtk_to_numpy(pd.GetArray("density"))
        assert (rho > 0).all() or name == "fluid_000000.vtu", name
        ids = sorted(vtk_to_numpy(pd.GetArray("id")).tolist())
        assert ids == list(range(800)), name
    else:
        assert g.GetNumberOfCells() == 6 and g.GetNumberOfPoints() == 48, name
        assert g.GetCellType(0) == vtk.VTK_HEXAHEDRON, name
        b = g.GetBounds()
        assert b[1] > b[0] and b[3] > b[2] and b[5] > b[4], b
print("sph_cli: vtk ok")
PY
ls "$dir/vtk" | grep -q tmp && fail "a temporary file was left behind"

# The headless render: a PNG per written frame and an animation (MP4 with ffmpeg, else GIF).
"$py" "$(dirname "$0")/../../scripts/render_sph.py" "$dir/vtk" --out "$dir/render" > "$dir/render.txt" ||
  fail "render_sph.py failed"
[[ $(ls "$dir"/render_*.png | wc -l) -eq 4 ]] || fail "render: expected 4 PNG frames"
[[ -s $dir/render.mp4 || -s $dir/render.gif ]] || fail "render: no animation"
echo "sph_cli: render ok"

# The dam break's front.
"$bin" sph --preset water --scenario dambreak --particles 500 --frames 3 --front-csv "$dir/front.csv" \
  > "$dir/water.txt" || fail "dam break failed"
grep -Eq "^ *status +ok$" "$dir/water.txt" || fail "dam break summary: $(cat "$dir/water.txt")"
head -1 "$dir/front.csv" | grep -qx "T,Z" || fail "front CSV header"
[[ $(wc -l < "$dir/front.csv") -gt 20 ]] || fail "front CSV too short"
# Its values: T = t sqrt(2 g / a) from 0 to the last frame's end (3 x 0.02 s, a = 0.05715 m,
# the column's width), increasing; Z = front / a from 1 (the column's face at rest: half the
# kernel's reach there is water) and moving out (the column falls), never behind the face.
python3 - "$dir/front.csv" <<'PY' || fail "front CSV values"
import csv, math, sys
rows = [(float(r["T"]), float(r["Z"])) for r in csv.DictReader(open(sys.argv[1]))]
t_end = 0.06 * math.sqrt(2 * 9.81 / 0.05715)
assert rows[0][0] == 0.0 and abs(rows[0][1] - 1.0) < 0.02, rows[0]
assert abs(rows[-1][0] - t_end) < 2e-6, (rows[-1], t_end)
assert all(b[0] > a[0] for a, b in zip(rows, rows[1:])), "T not increasing"
assert all(z >= 0.98 for _, z in rows), "front behind the column's face"
assert rows[-1][1] > 1.05, rows[-1]
PY
echo "sph_cli: front ok"

# SPHERIC Test 2's gauges: t,H1..H4 every 5 ms of simulated time to the end (0.1 s); at t = 0 the three gauges
# downstream are dry and H4 (in the column) reads the column's 0.55 m within the interpolation's
# resolution (a tenth of a spacing, 0.0917 m here); the column then drains, so H4 falls.
"$bin" sph --preset water --scenario marin --particles 900 --frames 5 --gauges-csv "$dir/gauges.csv" \
  > "$dir/marin.txt" || fail "marin failed"
head -1 "$dir/gauges.csv" | grep -qx "t,H1,H2,H3,H4" || fail "gauges CSV header"
python3 - "$dir/gauges.csv" <<'PY' || fail "gauges CSV values"
import csv, sys
rows = [[float(v) for v in r.values()] for r in csv.DictReader(open(sys.argv[1]))]
assert rows[0][:4] == [0.0, 0.0, 0.0, 0.0] and abs(rows[0][4] - 0.55) < 0.01, rows[0]
ts = [r[0] for r in rows]
# Row k: the first substep at or after k x 5 ms (the substeps here are under 5 ms).
assert len(rows) == 21 and all(0.005 * k - 1e-9 <= t < 0.005 * (k + 1) for k, t in enumerate(ts)), ts
assert rows[-1][4] < rows[0][4] - 0.005, (rows[0], rows[-1])
PY
echo "sph_cli: gauges ok"

# Checkpoint and restart: a run stopped at frame 20 and restarted to 40 writes the very files
# the uninterrupted run writes (every VTK frame and the series, byte for byte); the water dam
# break's front CSV likewise, across a restart in the middle of the surge.
"$bin" sph --preset seed --scenario dynamic --particles 800 --frames 40 --seed 3 \
  --vtk "$dir/ck_full" --every 10 > /dev/null || fail "checkpoint: the uninterrupted run failed"
"$bin" sph --preset seed --scenario dynamic --particles 800 --frames 20 --seed 3 \
  --vtk "$dir/ck_part" --every 10 --checkpoint "$dir/ck.bin" --checkpoint-every 10 > /dev/null ||
  fail "checkpoint: the first half failed"
# A name that is not one the series writes (frame 10's is fluid_000010.vtu) is not listed.
touch "$dir/ck_part/fluid_0000010.vtu"
"$bin" sph --restart "$dir/ck.bin" --frames 40 --vtk "$dir/ck_part" --every 10 --json \
  > "$dir/ck.json" || fail "checkpoint: the restart failed"
rm "$dir/ck_part/fluid_0000010.vtu"
for f in "$dir"/ck_full/*; do
  cmp -s "$f" "$dir/ck_part/$(basename "$f")" || fail "checkpoint: $(basename "$f") differs after a restart"
done
[[ $(ls "$dir/ck_full" | wc -l) -eq $(ls "$dir/ck_part" | wc -l) ]] || fail "checkpoint: other files"
python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['restarted_at_frame'] == 20" "$dir/ck.json" ||
  fail "checkpoint: the restart frame is not reported"
"$bin" sph --preset water --scenario dambreak --particles 500 --frames 4 \
  --front-csv "$dir/front_full.csv" > /dev/null || fail "checkpoint: water run failed"
"$bin" sph --preset water --scenario dambreak --particles 500 --frames 2 \
  --checkpoint "$dir/water.bin" > /dev/null || fail "checkpoint: water first half failed"
"$bin" sph --preset water --restart "$dir/water.bin" --frames 4 \
  --front-csv "$dir/front_part.csv" --checkpoint "$dir/water.bin" > /dev/null ||
  fail "checkpoint: water restart failed"
cmp -s "$dir/front_full.csv" "$dir/front_part.csv" || fail "checkpoint: the front differs after a restart"
"$bin" sph --preset water --scenario marin --particles 900 --frames 4 \
  --gauges-csv "$dir/gauges_full.csv" > /dev/null || fail "checkpoint: marin run failed"
"$bin" sph --preset water --scenario marin --particles 900 --frames 2 \
  --checkpoint "$dir/marin.bin" > /dev/null || fail "checkpoint: marin first half failed"
"$bin" sph --restart "$dir/marin.bin" --frames 4 --gauges-csv "$dir/gauges_part.csv" > /dev/null ||
  fail "checkpoint: marin restart failed"
cmp -s "$dir/gauges_full.csv" "$dir/gauges_part.csv" || fail "checkpoint: the gauges differ after a restart"
echo "sph_cli: checkpoint ok"

# Interrupted (SLURM's warning signal, SIGUSR1; SIGTERM at the limit): the run ends at the next
# frame's end with exit 0 and status interrupted, writes its checkpoint there, leaves no
# temporary file, and a restart from it writes the uninterrupted run's files byte for byte.
# The signal is sent once the fifth frame's VTK exists (the wait is a guard, not the outcome).
for sig in USR1 TERM; do
  rm -rf "$dir/int" "$dir/int.bin"
  "$bin" sph --preset seed --scenario dynamic --particles 800 --seed 5 --frames 100000 \
    --vtk "$dir/int" --every 1 --checkpoint "$dir/int.bin" --checkpoint-every 1000000 --json \
    > "$dir/int.json" 2> "$dir/int.err" &
  pid=$!
  # Wait for the event, not a clock: the 600 s limit only turns a hang into a failure, and a
  # run that ends before its fifth frame is a failure too.
  for ((waited = 0; ; ++waited)); do
    [[ -e $dir/int/fluid_000005.vtu ]] && break
    kill -0 "$pid" 2> /dev/null || fail "interrupted ($sig): the run ended before its fifth frame"
    ((waited < 6000)) || { kill -KILL "$pid"; fail "interrupted ($sig): no fifth frame in 600 s"; }
    sleep 0.1
  done
  kill -"$sig" "$pid"
  wait "$pid" || fail "interrupted ($sig): exit $? ($(cat "$dir/int.err"))"
  python3 - "$dir/int.json" "$sig" <<'PY' || fail "interrupted ($sig): report"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["status"] == "interrupted" and j["interrupted_by"] == "SIG" + sys.argv[2], j
assert 5 <= j["frames"] < 100000 and j["checkpoint"].endswith("int.bin"), j
PY
  ! ls "$dir/int" | grep -q "tmp" || fail "interrupted ($sig): a temporary file was left: $(ls "$dir/int" | grep tmp)"
done
stopped=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['frames'])" "$dir/int.json")
"$bin" sph --restart "$dir/int.bin" --frames $((stopped + 5)) --vtk "$dir/int" --every 1 > /dev/null ||
  fail "interrupted: the restart failed"
"$bin" sph --preset seed --scenario dynamic --particles 800 --seed 5 --frames $((stopped + 5)) \
  --vtk "$dir/int_ref" --every 1 > /dev/null || fail "interrupted: the reference run failed"
for f in "$dir"/int_ref/*; do
  cmp -s "$f" "$dir/int/$(basename "$f")" || fail "interrupted: $(basename "$f") differs after the restart"
done
echo "sph_cli: interrupt ok"

# Bad input: exit 2, one line on stderr, nothing written.
bad() {
  local what=$1; shift
  rm -rf "$dir/bad.json" "$dir/badvtk"
  "$bin" sph "$@" --output "$dir/bad.json" > /dev/null 2> "$dir/err.txt"
  local rc=$?
  [[ $rc -eq 2 ]] || fail "$what: exit $rc, expected 2 ($(cat "$dir/err.txt"))"
  [[ $(wc -l < "$dir/err.txt") -eq 1 ]] || fail "$what: stderr is not one line: $(cat "$dir/err.txt")"
  [[ ! -e $dir/bad.json && ! -e $dir/badvtk ]] || fail "$what: wrote output on bad input"
}
bad "no particles" --particles 0
bad "no frames" --frames 0
bad "unknown preset" --preset lava
bad "unknown scenario" --scenario ocean
bad "dam break with the seed preset" --preset seed --scenario dambreak
bad "water with boxes" --preset water --scenario static
bad "over the memory budget" --particles 100000000 --memory-mb 64 --vtk "$dir/badvtk"
bad "front without a dam break" --front-csv "$dir/f.csv"
bad "unwritable vtk" --vtk /nonexistent-dir/vtk
bad "unwritable front" --preset water --front-csv /nonexistent-dir/f.csv
bad "gauges without marin" --preset water --gauges-csv "$dir/g.csv"
grep -q "needs --scenario marin" "$dir/err.txt" || fail "gauges without marin: $(cat "$dir/err.txt")"
bad "marin too coarse" --preset water --scenario marin --particles 675
grep -q "particles 676 or more" "$dir/err.txt" || fail "marin too coarse: $(cat "$dir/err.txt")"
bad "empty gauges path" --preset water --scenario marin --gauges-csv ""
bad "gauges onto the JSON" --preset water --scenario marin --particles 900 --gauges-csv "$dir/bad.json"
grep -q "also another output's file" "$dir/err.txt" || fail "gauges onto the JSON: $(cat "$dir/err.txt")"
bad "negative threads" --threads -1
bad "unknown backend" --backend gpu
# Damaged and foreign checkpoints, and a restart that names another problem.
head -c 500 "$dir/ck.bin" > "$dir/cut.bin"
cp "$dir/ck.bin" "$dir/flip.bin"
printf '\x7f' | dd of="$dir/flip.bin" bs=1 seek=20000 conv=notrunc 2> /dev/null
echo "not a checkpoint" > "$dir/foreign.bin"
bad "cut checkpoint" --restart "$dir/cut.bin"
grep -q "cut short" "$dir/err.txt" || fail "cut checkpoint: $(cat "$dir/err.txt")"
bad "damaged checkpoint" --restart "$dir/flip.bin"
grep -q "checksum" "$dir/err.txt" || fail "damaged checkpoint: $(cat "$dir/err.txt")"
bad "foreign checkpoint" --restart "$dir/foreign.bin"
grep -q "not an hpcplan fluid checkpoint" "$dir/err.txt" || fail "foreign: $(cat "$dir/err.txt")"
bad "missing checkpoint" --restart "$dir/none.bin"
# A checkpoint resealed with a sound checksum around a NaN gauge reading, and around one gauge
# row too few for its time: each refused as damaged.
python3 - "$dir/marin.bin" "$dir" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
magic = b"hpcplan fluid checkpoint\n"
n = struct.unpack_from("<Q", data, len(magic) + 4)[0]
at = len(magic) + 4 + 8 + n
head, size = data[:at], struct.unpack_from("<Q", data, at)[0]
payload = data[at + 8:at + 8 + size]
def seal(name, p):
    h = 0xcbf29ce484222325
    for b in p:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    open(f"{sys.argv[2]}/{name}", "wb").write(head + struct.pack("<Q", len(p)) + p + struct.pack("<Q", h))
seal("nan.bin", payload[:-8] + struct.pack("<d", float("nan")))
rows, cols = struct.unpack_from("<QQ", payload, len(payload) - 16 - 8 * 5 * 9)
assert (rows, cols) == (9, 5), (rows, cols)  # 2 frames: t = 0, 5, ..., 40 ms
short = payload[:len(payload) - 16 - 8 * 5 * 9] + struct.pack("<QQ", 7, 5) + payload[len(payload) - 8 * 5 * 7:]
seal("short.bin", short)
PY
bad "NaN gauge reading" --restart "$dir/nan.bin" --frames 4
grep -q "not finite" "$dir/err.txt" || fail "NaN gauge reading: $(cat "$dir/err.txt")"
bad "gauge rows too few" --restart "$dir/short.bin" --frames 4
grep -q "probe rows that do not fit" "$dir/err.txt" || fail "gauge rows too few: $(cat "$dir/err.txt")"
bad "checkpoint of another problem" --restart "$dir/ck.bin" --particles 900
grep -q "continues --preset seed --scenario dynamic --particles 800" "$dir/err.txt" ||
  fail "another problem: $(cat "$dir/err.txt")"
bad "restart past --frames" --restart "$dir/ck.bin" --frames 10
bad "unwritable checkpoint" --checkpoint /nonexistent-dir/c.bin
bad "empty restart path" --restart ""
bad "empty checkpoint path" --checkpoint ""
bad "restart from a device" --restart /dev/zero
bad "checkpoint onto the front CSV" --preset water --checkpoint "$dir/same.csv" --front-csv "$dir/same.csv"
grep -q "also another output's file" "$dir/err.txt" || fail "same file: $(cat "$dir/err.txt")"
# --backend cuda: refused with its reason where no GPU can run it (this build may or may not have
# the backend); where one can, it runs and reports its backend.
if "$bin" sph --backend cuda --particles 500 --frames 2 --json > "$dir/cuda.json" 2> "$dir/err.txt"; then
  python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['backend'] == 'cuda'" "$dir/cuda.json" ||
    fail "a cuda run does not report its backend"
else
  bad "cuda where it cannot run" --backend cuda
  grep -q -- "--backend cuda: " "$dir/err.txt" || fail "cuda refusal without its reason"
fi
echo "sph_cli: ok"
