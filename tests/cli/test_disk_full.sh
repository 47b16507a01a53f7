#!/usr/bin/env bash
# A full disk, for real: a 1 MiB tmpfs mounted for the test. Every long job's outputs (the grid's
# checkpoints and --output, the fluid's VTK series and checkpoint, the simulator's checkpoint
# and CSV) fail with exit 1 and one line naming the file and "No space left on device", and no
# temporary file is left behind. Run by a user other than root, who cannot mount, the test is
# skipped (exit 77) and prints why. As root (the test command in CI) a tmpfs that cannot be
# mounted is a failure, not a skip: the test would otherwise pass without testing anything.
# Usage: test_disk_full.sh HPCPLAN
set -uo pipefail
bin=$1
mnt=$(mktemp -d)
cleanup() { umount "$mnt" 2>/dev/null; rmdir "$mnt"; }
trap cleanup EXIT
fail() { echo "disk_full: FAIL: $*" >&2; exit 1; }
if ! why=$(mount -t tmpfs -o size=1M tmpfs "$mnt" 2>&1); then
  [[ $(id -u) -eq 0 ]] || {
    echo "disk_full: SKIPPED: user $(id -un) cannot mount a tmpfs (needs root): $why"
    exit 77
  }
  fail "cannot mount a 1 MiB tmpfs on $mnt, although running as root: $why"
fi

full() {  # full WHAT ARGS...: the run fails with exit 1 and a one-line ENOSPC message
  local what=$1
  shift
  rm -rf "${mnt:?}"/*
  # All but 4 KiB taken: the outputs below are larger.
  head -c $((1024 * 1024 - 4 * 1024)) /dev/zero > "$mnt/filler" 2>/dev/null
  local err rc
  err=$("$bin" "$@" 2>&1 > /dev/null)
  rc=$?
  [[ $rc -eq 1 ]] || fail "$what: exit $rc, not 1 ($err)"
  [[ $(wc -l <<< "$err") -eq 1 && $err == *"No space left on device"* && $err == *"$mnt/"* ]] ||
    fail "$what: unclear message: $err"
  local left
  left=$(find "$mnt" -name '*.tmp*')
  [[ -z $left ]] || fail "$what: temporary files left behind: $left"
  echo "disk_full: $what: exit 1, $err"
}
# The grid's checkpoints (3.3 MB) and a JSON result with a path of 60 KB.
full "grid --checkpoint" grid --dims 4 --extent 60 --algo bfs --engine dense --threads 2 \
  --checkpoint "$mnt/ck" --checkpoint-every 0.0001
full "grid --output" grid --dims 2 --extent 3000 --algo bfs --threads 2 --path \
  --output "$mnt/out.json"
full "sph --vtk" sph --particles 1500 --frames 2 --threads 2 --vtk "$mnt/vtk" --every 1
full "sph --checkpoint" sph --particles 1500 --frames 2 --threads 2 --checkpoint "$mnt/fluid.ckpt"
full "sim --trajectory" sim --particles 300 --runs 1 --max-sim-s 5 --threads 2 \
  --trajectory "$mnt/t.csv"
full "sim --checkpoint" sim --particles 300 --runs 1 --max-sim-s 5 --threads 2 \
  --trajectory "$mnt/t2.csv" --checkpoint "$mnt/sim.ckpt"
echo "disk_full: ok"
