#!/usr/bin/env bash
# Do MPI ranks pay on a mechanism's configuration space? A* on OMPL's kinematic chain (n links
# in the horn, 4n joint cells per axis: CELLS_PER_LINK=4): for each n, ROUNDS rounds of one job on P
# ranks with --compare-serial, so rank 0 runs the serial engine on the same query first, in the
# same job, and the two alternate round by round. Prints each round's serial and distributed
# time and the median speedup, with the search overhead (states the ranks expanded over the
# serial engine's) and the costs (which must agree).
#   bash bench/cspace_ranks.sh [build/bin/hpcplan]   (LINKS="6 7", RANKS=2, ROUNDS=5,
#                                                    MODE=async, MOVES=pairs, CELLS_PER_LINK=4,
#                                                    EXTRA='--owner-coarsen 1')
set -euo pipefail
bin=${1:-build/bin/hpcplan}
links=${LINKS:-6 7}
ranks=${RANKS:-2}
rounds=${ROUNDS:-5}
mode=${MODE:-async}
moves=${MOVES:-pairs}
per_link=${CELLS_PER_LINK:-4}
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
echo "hpcplan cspace ranks: chain A*, $ranks ranks ($mode), moves $moves, $rounds rounds; $(nproc) cores, $(date -u +%F)"
printf '%5s %5s %10s %10s %8s %9s %10s %10s\n' links round serial_ms ranks_ms speedup overhead cost ranks_cost
for n in $links; do
  speedups=()
  for ((r = 1; r <= rounds; ++r)); do
    line=$(mpirun -np "$ranks" --oversubscribe "$bin" grid --world chain --dims "$n" --cells $((per_link * n)) --moves "$moves" \
      --mode "$mode" ${EXTRA:-} --compare-serial --json | python3 -c '
import json, sys
j = json.load(sys.stdin)
s = j["serial_reference"]
print("%.1f %.1f %.3f %.3f %.6f %.6f" % (s["time_ms"], j["time_ms"], s["speedup"],
                                        s["search_overhead"], s["cost"], j["cost"]))')
    read -r sms pms sp ov sc pc <<<"$line"
    printf '%5s %5s %10s %10s %8s %9s %10s %10s\n' "$n" "$r" "$sms" "$pms" "${sp}x" "$ov" "$sc" "$pc"
    [[ $sc == "$pc" ]] || { echo "cspace_ranks: costs differ ($sc vs $pc)" >&2; exit 1; }
    speedups+=("$sp")
  done
  median=$(printf '%s\n' "${speedups[@]}" | sort -g | awk '{a[NR]=$1} END{print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}')
  echo "links $n: median speedup ${median}x on $ranks ranks"
done
