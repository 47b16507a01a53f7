#!/usr/bin/env bash
# The water preset against experiment, at three resolutions:
#   dam break: surge front Z = x/a against T = t sqrt(2g/a) beside Martin and Moyce (1952),
#              12, 20 and 30 particles across the column (864, 4,000 and 13,500 particles),
#              the error at each experimental point with 0.8 <= T <= 3, raw and with the
#              literature's gate offset (T + 0.175) as a second figure;
#   tank:      pressure at mid-depth and the largest density error after settling, at
#              4,000, 32,000 and 108,000 particles.
# Writes results/sph_validation.csv, results/sph_damfront_<n>.csv and, with matplotlib,
# results/sph_dambreak.png. Usage: bench/sph_validation.sh [BUILD_DIR=build]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build}/bin/hpcplan
py=/usr/bin/python3
[[ -x $py ]] || py=python3
mkdir -p results
for n in 864 4000 13500; do
  echo "dam break, $n particles" >&2
  "$bin" sph --preset water --scenario dambreak --particles "$n" --frames 9 \
    --front-csv "results/sph_damfront_$n.csv" --json > "results/sph_dambreak_$n.json"
done
for n in 4000 32000 108000; do
  echo "tank, $n particles" >&2
  "$bin" sph --preset water --scenario tank --particles "$n" --frames 25 --vtk "results/sph_tank_$n" \
    --every 5 --json > "results/sph_tank_$n.json"
done
"$py" - <<'PY'
import csv, json
import numpy as np
exp = [tuple(map(float, r)) for r in csv.reader(
    l for l in open("../shared/validation/martin_moyce_1952.csv") if not l.startswith("#"))
    if r[0] != "T"]
rows = []
pts = [(t, z) for t, z in exp if 0.8 <= t <= 3]
# Raw: T as simulated (the gate vanishes at t = 0). Offset: the experiment's clock read as
# T + 0.175, the gate-lift offset that the Lethe and OpenFOAM comparisons apply; reported beside
# the raw figure, never instead of it.
for label, shift in (("raw", 0.0), ("offset T + 0.175", 0.175)):
    print(f"Front Z, {label}:")
    print("| particles | dx / a | " + " | ".join(f"T={t:.3f} (exp Z={z:.3f})" for t, z in pts) + " | max error |")
    print("|---" * (3 + len(pts)) + "|")
    for n in (864, 4000, 13500):
        f = list(csv.DictReader(open(f"results/sph_damfront_{n}.csv")))
        T = np.array([float(r["T"]) for r in f]); Z = np.array([float(r["Z"]) for r in f])
        j = json.load(open(f"results/sph_dambreak_{n}.json"))
        cells, worst = [], 0.0
        for t, z in pts:
            zs = float(np.interp(t - shift, T, Z)); err = (zs - z) / z
            worst = max(worst, abs(err))
            cells.append(f"{zs:.3f} ({err*100:+.1f}%)")
            rows.append([f"dambreak_{label.split()[0]}", n, t, z, zs, err])
        print(f"| {j['particles']} | {j['particle_spacing']/0.05715:.4f} | " + " | ".join(cells) + f" | {worst*100:.1f}% |")
    print()
import vtk
from vtk.util.numpy_support import vtk_to_numpy
print()
print("| particles | mid-depth pressure (Pa) | hydrostatic | error | max density error |")
print("|---|---|---|---|---|")
for n in (4000, 32000, 108000):
    j = json.load(open(f"results/sph_tank_{n}.json"))
    ps = []
    for fr in (20, 25):
        r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(f"results/sph_tank_{n}/fluid_{fr:06d}.vtu"); r.Update()
        g = r.GetOutput(); z = vtk_to_numpy(g.GetPoints().GetData())[:, 2]
        p = vtk_to_numpy(g.GetPointData().GetArray("pressure"))
        m = (z > 0.1) & (z < 0.4)
        slope, icpt = np.polyfit(z[m], p[m], 1)
        ps.append(icpt + slope * 0.25)
    pm = float(np.mean(ps)); ref = 1000 * 9.81 * 0.25
    print(f"| {j['particles']} | {pm:.1f} | {ref:.1f} | {(pm-ref)/ref*100:+.1f}% | {j['max_density_error']:.4f} |")
    rows.append(["tank", j["particles"], 0.25, ref, pm, (pm - ref) / ref])
with open("results/sph_validation.csv", "w", newline="") as out:
    w = csv.writer(out); w.writerow(["case", "particles", "x", "reference", "simulated", "relative_error"]); w.writerows(rows)
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot([t for t, _ in exp], [z for _, z in exp], "ko", label="Martin & Moyce (1952)")
    for n in (864, 4000, 13500):
        f = list(csv.DictReader(open(f"results/sph_damfront_{n}.csv")))
        j = json.load(open(f"results/sph_dambreak_{n}.json"))
        ax.plot([float(r["T"]) for r in f], [float(r["Z"]) for r in f],
                label=f"hpcplan water, {j['particles']} particles, dx = a/{round(0.05715 / j['particle_spacing'])}")
    ax.axvspan(0.8, 3.0, color="0.9", zorder=0)
    ax.set_xlim(0, 3.5); ax.set_ylim(0.9, 5); ax.set_xlabel("T = t sqrt(2g/a)"); ax.set_ylabel("Z = x/a")
    ax.legend(); fig.tight_layout(); fig.savefig("results/sph_dambreak.png", dpi=120)
except ImportError:
    pass
PY
