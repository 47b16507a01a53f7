#!/usr/bin/env bash
# SPHERIC Test 2 (MARIN's dam break with an obstacle, Kleefsman et al. 2005): the water
# preset's heights at the four gauges against the experiment, at several resolutions.
#   resolutions: nz particles over the column's 0.55 m height (dx = 0.55 / nz); the particle
#                count asked for is 4.06 nz^3 (the column is 1.228 x 1 x 0.55 m);
#   figures per gauge: the mean absolute height error over the run (m, and as a fraction of the
#   column's height) and the time the water first stands 0.05 m deep there (simulated against
#   measured). The experiment's columns are mapped to gauges by where they lie (see
#   bench/data/marin_dambreak_heights.csv): H3 (x = 1.488 m) is the first the water reaches.
# Writes results/sph_marin_<nz>.csv (t,H1..H4), results/sph_marin.csv (the figures) and, with
# matplotlib, results/sph_marin.png.
# Usage: bench/sph_marin.sh [BUILD_DIR=build] [SECONDS=6] [THREADS=2] [NZ...=8 11 16]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
seconds=${2:-6}
threads=${3:-2}
shift $(($# < 3 ? $# : 3))
resolutions=("$@")
[[ ${#resolutions[@]} -gt 0 ]] || resolutions=(8 11 16)
bin=$build/bin/hpcplan
py=/usr/bin/python3
[[ -x $py ]] || py=python3
mkdir -p results
frames=$("$py" -c "print(round($seconds / 0.02))")
for nz in "${resolutions[@]}"; do
  n=$("$py" -c "print(round((1.228 / 0.55) * (1 / 0.55) * $nz ** 3))")
  echo "marin, nz = $nz ($n particles asked for), $seconds s on $threads threads" >&2
  "$bin" sph --preset water --scenario marin --particles "$n" --frames "$frames" --threads "$threads" \
    --gauges-csv "results/sph_marin_$nz.csv" --json > "results/sph_marin_$nz.json"
done
"$py" - "$seconds" "${resolutions[@]}" <<'PY'
import csv, json, sys
import numpy as np
seconds = float(sys.argv[1]); resolutions = [int(a) for a in sys.argv[2:]]
exp = np.loadtxt("bench/data/marin_dambreak_heights.csv", delimiter=",", comments="#", skiprows=4)
# The file's columns 1..4 are the gauges at x = 1.488, 0.992, 0.496 and 2.638 m (H3, H2, H1, H4).
measured = {"H1": exp[:, 3], "H2": exp[:, 2], "H3": exp[:, 1], "H4": exp[:, 4]}
te = exp[:, 0]
keep = te <= seconds
def arrival(t, h, level=0.05):
    above = np.nonzero(h >= level)[0]
    return float(t[above[0]]) if len(above) else float("nan")
rows = []
print(f"SPHERIC Test 2, 0 <= t <= {seconds:g} s: mean |H_sim - H_exp| (m; % of the 0.55 m column), "
      "and the time the water first stands 0.05 m deep (s, simulated / measured)\n")
print("| nz | dx (m) | particles (fluid + wall) | ms per frame | " +
      " | ".join(f"{g} error" for g in measured) + " | " + " | ".join(f"{g} arrival" for g in ("H3", "H2", "H1")) + " |")
print("|---" * (4 + len(measured) + 3) + "|")
for nz in resolutions:
    sim = list(csv.DictReader(open(f"results/sph_marin_{nz}.csv")))
    ts = np.array([float(r["t"]) for r in sim])
    j = json.load(open(f"results/sph_marin_{nz}.json"))
    cells, arrivals = [], []
    for g, h in measured.items():
        hs = np.array([float(r[g]) for r in sim])
        err = float(np.mean(np.abs(np.interp(te[keep], ts, hs) - h[keep])))
        cells.append(f"{err:.3f} ({err / 0.55 * 100:.1f}%)")
        rows.append([nz, j["particle_spacing"], g, "mean_abs_error_m", err])
        if g != "H4":
            a_sim, a_exp = arrival(ts, hs), arrival(te, h)
            arrivals.append((g, f"{a_sim:.3f} / {a_exp:.3f}"))
            rows.append([nz, j["particle_spacing"], g, "arrival_s_sim", a_sim])
            rows.append([nz, j["particle_spacing"], g, "arrival_s_exp", a_exp])
    order = dict(arrivals)
    print(f"| {nz} | {j['particle_spacing']:.4f} | {j['particles']:,} + {j['wall_particles']:,} | "
          f"{j['ms_per_frame_median']:.0f} | " + " | ".join(cells) + " | " +
          " | ".join(order[g] for g in ("H3", "H2", "H1")) + " |")
with open("results/sph_marin.csv", "w", newline="") as out:
    w = csv.writer(out); w.writerow(["nz", "dx", "gauge", "figure", "value"]); w.writerows(rows)
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(10, 6), sharex=True)
    for ax, (g, h) in zip(axes.flat, measured.items()):
        ax.plot(te[keep], h[keep], "k-", lw=1.5, label="MARIN (Kleefsman et al. 2005)")
        for nz in resolutions:
            sim = list(csv.DictReader(open(f"results/sph_marin_{nz}.csv")))
            ax.plot([float(r["t"]) for r in sim], [float(r[g]) for r in sim], lw=1,
                    label=f"hpcplan water, dx = {0.55 / nz:.3f} m")
        ax.set_title(g); ax.set_ylabel("height (m)")
    for ax in axes[1]: ax.set_xlabel("t (s)")
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout(); fig.savefig("results/sph_marin.png", dpi=110)
    print("\nwrote results/sph_marin.png")
except ImportError:
    print("\n(matplotlib missing: no plot)")
PY
