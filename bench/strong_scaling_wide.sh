#!/usr/bin/env bash
# Strong scaling beyond two cores: P = 1, 2, 4, 8, 16 (or RANKS) on one problem, the
# distributed search timed against the serial engine in the same job (interleaved, median of
# REPEATS), with the machine's ceiling (the serial search on every rank at once) for P > 1.
# Works with any mpirun on the PATH, e.g. a relocated Debian Open MPI carried to a machine
# without Debian packages (docs/PERFORMANCE.md, issue 17). Appends to OUT/strong_scaling_wide.csv.
# Usage: bench/strong_scaling_wide.sh BIN OUT [dims extent]
#   env: RANKS, REPEATS, MODES, COARSEN, SLABS (slab widths, 0 = the hash; "P" is the extent
#   split into P contiguous slabs, "2P" into 2P slabs dealt round, so each rank gets two)
set -uo pipefail
bin=${1:?hpcplan_mpi_scaling} out=${2:?OUT_DIR} dims=${3:-6} extent=${4:-11}
ranks=${RANKS:-1 2 4 8 16} repeats=${REPEATS:-2} modes=${MODES:-async} coarsen=${COARSEN:-0,1}
slabs=${SLABS:-0}
mkdir -p "$out"
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
csv=$out/strong_scaling_wide.csv
for p in $ranks; do
  extra=()
  widths=()
  for w in ${slabs//,/ }; do
    case $w in
      P) widths+=($(((extent + p - 1) / p))) ;;
      2P) widths+=($(((extent + 2 * p - 1) / (2 * p)))) ;;
      *) widths+=("$w") ;;
    esac
  done
  list=$(IFS=,; echo "${widths[*]}")
  ((p > 1)) && extra=(--modes "$modes" --coarsen "$coarsen" --slabs "$list" --ceiling)
  t0=$SECONDS
  mpirun --oversubscribe --bind-to core -np "$p" "$bin" --dims "$dims" --extent "$extent" \
    --algo dijkstra --repeats "$repeats" "${extra[@]}" --label "wide_d$dims" --csv "$csv" \
    > "$out/np$p.log" 2>&1
  echo "strong_scaling_wide: P=$p rc=$? in $((SECONDS - t0)) s" >&2
done
