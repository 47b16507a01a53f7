#!/usr/bin/env bash
# Writes the checkpoint seeds of the fuzz corpus with a built hpcplan: small real checkpoints
# (hpcplan sph and sim --checkpoint) and their payloads (the bytes inside core's envelope,
# core/checkpoint_file.hpp, which the targets also decode alone). Run it again after a change
# of either checkpoint's format (or of hpcplan's version, which the envelope names): the old
# seeds would then be refused at their first bytes and the fuzzing would stay shallow.
# Usage: tests/fuzz/corpus/make_checkpoints.sh [BIN=build/bin/hpcplan]
set -euo pipefail
cd "$(dirname "$0")"
bin=$(realpath "${1:-../../../build/bin/hpcplan}")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
payload() {  # payload FILE OUT: the envelope's payload (magic line, format, version, size)
  python3 - "$1" "$2" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
at = data.index(b"\n") + 1 + 4
n, = struct.unpack_from("<Q", data, at)
at += 8 + n
size, = struct.unpack_from("<Q", data, at)
at += 8
assert at + size + 8 == len(data), "not one envelope"
open(sys.argv[2], "wb").write(data[at:at + size])
PY
}
f=fuzz_fluid_checkpoint
for scenario in particles dynamic; do
  "$bin" sph --preset seed --scenario "$scenario" --particles 2 --frames 2 \
    --checkpoint "$tmp/$scenario.ckpt" > /dev/null
done
cp "$tmp/dynamic.ckpt" "$f/seed_dynamic.ckpt"
payload "$tmp/particles.ckpt" "$f/seed_particles.payload"
payload "$tmp/dynamic.ckpt" "$f/seed_dynamic.payload"
s=fuzz_sim_checkpoint
"$bin" sim --particles 20 --settle-frames 1 --max-sim-s 0.2 --replan-every 5 --runs 2 \
  --checkpoint "$tmp/two_runs.ckpt" > /dev/null
"$bin" sim --particles 20 --scenario dynamic --algo dstar_lite --settle-frames 1 --max-sim-s 0.1 \
  --replan-every 3 --trajectory "$tmp/trajectory.csv" --checkpoint "$tmp/trajectory.ckpt" > /dev/null
cp "$tmp/two_runs.ckpt" "$s/two_runs.ckpt"
payload "$tmp/two_runs.ckpt" "$s/two_runs.payload"
payload "$tmp/trajectory.ckpt" "$s/trajectory.payload"
# The dense engine's grid checkpoint: its target writes its own seeds (a genuine file and its
# engine payload for each of its four runs) when asked, from the build's replay binary.
grid=$(dirname "$bin")/fuzz_grid_checkpoint_replay
if [[ -x $grid ]]; then
  rm -f fuzz_grid_checkpoint/*
  echo x > "$tmp/any"
  HPCPLAN_FUZZ_WRITE_SEEDS=$PWD/fuzz_grid_checkpoint "$grid" --mutations 1 "$tmp/any" > /dev/null
fi
echo "make_checkpoints: seeds written into $(pwd)/{$f,$s}"
