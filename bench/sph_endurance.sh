#!/usr/bin/env bash
# Long runs that must end sound (every number finite, every particle in the box and out of the
# obstacles, every frame): the seed preset's three scenarios at 25,000 particles for 10,000
# frames (200 s of simulated time), and the water tank at 4,000 particles for 500 frames (10 s).
# Writes results/sph_endurance.csv. Usage: bench/sph_endurance.sh [BUILD_DIR=build] [FRAMES=10000]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build}/bin/hpcplan
frames=${2:-10000}
mkdir -p results
out=results/sph_endurance.csv
echo "preset,scenario,particles,frames,status,substeps,ms_per_frame_median,ms_per_frame_max,kinetic_energy,max_speed,neighbours_max,seconds" > "$out"
run() {  # preset scenario particles frames
  local start=$SECONDS json
  json=$("$bin" sph --preset "$1" --scenario "$2" --particles "$3" --frames "$4" --seed 1 --json)
  ELAPSED=$((SECONDS - start)) PRESET=$1 SCENARIO=$2 python3 -c '
import json, os, sys
j = json.loads(sys.stdin.read())
status = j["status"] if j["status"] == "ok" else "unstable@%s" % j["unstable_frame"]
print(",".join(str(x) for x in [os.environ["PRESET"], os.environ["SCENARIO"], j["particles"],
      j["frames"], status, j["substeps"], round(j["ms_per_frame_median"], 3),
      round(j["ms_per_frame_max"], 3), j["kinetic_energy"], j["max_speed"], j["neighbours_max"],
      os.environ["ELAPSED"]]))' <<< "$json" >> "$out"
  tail -1 "$out"
}
for scenario in particles static dynamic; do run seed "$scenario" 25000 "$frames"; done
run water tank 4000 $((frames / 20))
