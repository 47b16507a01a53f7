#!/usr/bin/env bash
# The seed preset against the seed authors' own CPU step, side by side (issue 33). Their code
# (github.com/aneangel/particlePaths, MIT) is a peer, never part of this project: it is read
# from a checkout given on the command line and built into a temporary directory with our
# headless driver (bench/seed_peer/driver.cpp), which times their updatePhysics, one call per
# 0.02 s frame. Ours is `hpcplan sph --preset seed --scenario dynamic`. For N = 1,500 / 12,500 /
# 25,000 each round runs their driver (serial, 1 thread) and ours with 1 and 2 threads, in an
# order that alternates between rounds; each figure is the median of ROUNDS rounds of the
# per-frame median. Prints a Markdown table and writes results/seed_peer.csv (one row per run).
#
# Usage: bench/seed_peer.sh PEER_DIR [BUILD_DIR=build] [ROUNDS=3]
#   PEER_DIR holds their sources (particle.cpp, particle.h, metrics.h), e.g. from
#   `git clone https://github.com/aneangel/particlePaths DIR`, or from a local mirror
#   `git -C MIRROR archive HEAD | tar -x -C DIR`.
#   FRAMES (default 200) timed frames per run, on both sides; WARMUP (default 20) untimed
#   frames before their timed ones (ours has no warm-up option; its median absorbs the start).
set -euo pipefail
cd "$(dirname "$0")/.."
peer=${1:-}
build=${2:-build}
rounds=${3:-3}
frames=${FRAMES:-200}
warmup=${WARMUP:-20}

if [[ -z $peer || ! -f $peer/particle.cpp || ! -f $peer/particle.h || ! -f $peer/metrics.h ]]; then
  echo "seed_peer: PEER_DIR must hold the seed authors' particle.cpp/.h and metrics.h; get them with: git clone https://github.com/aneangel/particlePaths PEER_DIR" >&2
  exit 2
fi
if [[ ! -x $build/bin/hpcplan ]]; then
  echo "seed_peer: $build/bin/hpcplan is missing; build it with: cmake --build $build --target hpcplan" >&2
  exit 2
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Their Makefile's flags without CUDA and GL (particle.cpp includes neither). -fwrapv because
# their gridHash multiplies cell indices by ~1e8 in int: the overflow is undefined, and g++ -O3
# drops their `hash < 0` fix-up on that ground, so the step crashes in buildSpatialGrid from the
# first frame. -fwrapv defines the wrap-around their hash is written for (it only forbids the
# optimiser to assume that signed arithmetic never overflows, in their code and our driver).
g++ -std=c++17 -O3 -march=native -Wall -Wextra -Wno-deprecated-declarations -fwrapv \
  -I"$peer" -o "$tmp/peer_driver" bench/seed_peer/driver.cpp "$peer/particle.cpp"

# Ours from a copy, so that every round times one binary even if the build tree is rebuilt
# while this runs (a half-linked file is not executable).
cp "$build/bin/hpcplan" "$tmp/hpcplan"

rows=$tmp/rows.csv
echo "round,program,particles,threads,frames,ms_per_frame_median,substeps_per_frame,neighbours_mean" > "$rows"

# One JSON object on stdin -> one CSV row (the peer takes one step per frame; ours reports the
# substeps of the whole run).
to_row() {
  /usr/bin/python3 -c '
import json, sys
r, prog, t = sys.argv[1:4]
j = json.load(sys.stdin)
print("%s,%s,%d,%s,%d,%.6g,%.6g,%.6g" % (r, prog, j["particles"], t, j["frames"],
      j["ms_per_frame_median"], j["substeps"] / j["frames"], j["neighbours_mean"]))' "$@"
}

run_peer() {  # round n
  "$tmp/peer_driver" "$2" "$warmup" "$frames" | to_row "$1" peer 1 >> "$rows"
}
run_ours() {  # round n threads
  "$tmp/hpcplan" sph --preset seed --scenario dynamic --particles "$2" --frames "$frames" \
    --threads "$3" --json | to_row "$1" ours "$3" >> "$rows"
}

for r in $(seq "$rounds"); do
  for n in 1500 12500 25000; do
    # Alternate who goes first, so that a drift in the machine's speed (other work, heat) does
    # not always land on the same program.
    if (( r % 2 )); then
      run_peer "$r" "$n"; run_ours "$r" "$n" 1; run_ours "$r" "$n" 2
    else
      run_ours "$r" "$n" 2; run_ours "$r" "$n" 1; run_peer "$r" "$n"
    fi
  done
done

mkdir -p results
cp "$rows" results/seed_peer.csv
/usr/bin/python3 - results/seed_peer.csv <<'PY'
import csv, statistics, sys
from collections import defaultdict
ms, sub, nb = defaultdict(list), defaultdict(list), defaultdict(list)
rounds = set()
for r in csv.DictReader(open(sys.argv[1])):
    k = (r["program"], int(r["particles"]), r["threads"])
    ms[k].append(float(r["ms_per_frame_median"]))
    sub[k].append(float(r["substeps_per_frame"]))
    nb[k].append(float(r["neighbours_mean"]))
    rounds.add(r["round"])
med = lambda d, k: statistics.median(d[k])
print(f"\nms per 0.02 s frame, seed preset's dynamic scenario (medians of {len(rounds)} rounds)\n")
print("| N | peer ms/frame (1 thread) | ours 1 thread | ours 2 threads "
      "| ratio peer/ours (2 threads) | ratio peer/ours (1 thread) "
      "| our substeps/frame | neighbours/particle peer, ours |")
print("|---|---|---|---|---|---|---|---|")
for n in sorted({k[1] for k in ms}):
    p, o1, o2 = med(ms, ("peer", n, "1")), med(ms, ("ours", n, "1")), med(ms, ("ours", n, "2"))
    print(f"| {n:,} | {p:.2f} | {o1:.2f} | {o2:.2f} | {p / o2:.1f} | {p / o1:.1f} "
          f"| {med(sub, ('ours', n, '1')):g} "
          f"| {med(nb, ('peer', n, '1')):.2f}, {med(nb, ('ours', n, '1')):.2f} |")
print("\nPeer: one updatePhysics (1 step) per frame; its neighbours are those its findNeighbors "
      "returns (it misses ~40% of the pairs, see bench/seed_peer/driver.cpp).")
PY
