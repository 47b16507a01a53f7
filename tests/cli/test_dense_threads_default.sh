#!/usr/bin/env bash
# The dense engine's default thread count is the process's share of the CPUs it may run on
# (its affinity mask), not every core of the machine: serial under taskset, and under mpirun
# with each rank bound to a core of its own (--bind-to core) or with the ranks sharing one set
# (--bind-to none: the set's CPUs over the ranks whose sets overlap). Each run reports its
# threads in the JSON (dense.threads), which must equal what the mask allows.
# Usage: test_dense_threads_default.sh HPCPLAN MPIRUN
set -uo pipefail
bin=$1
mpirun=$2
fail() { echo "dense_threads_default: FAIL: $*" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

# 4D extent 60: about 130,000 free states a level, enough for the per-level rule to want 3
# threads (kDenseStatesPerThreadLevel), so the CPU share is what limits them.
problem=(grid --dims 4 --extent 60 --algo bfs --engine dense --json)
cpus=$(nproc)  # this process's CPU set (nproc reads the affinity mask)
threads() { python3 -c 'import json,sys; print(json.load(sys.stdin)["dense"]["threads"])'; }

got=$("$bin" "${problem[@]}" | threads) || fail "the serial run failed"
want=$((cpus < 3 ? cpus : 3))
[[ $got == "$want" ]] || fail "serial on $cpus CPUs: $got threads, not $want"
# OpenMP's binding pins the main thread to its first place before main runs: the default
# counts the places' CPUs, not the pinned thread's one.
for bind in OMP_PROC_BIND=true OMP_PLACES=cores; do
  got=$(env "$bind" "$bin" "${problem[@]}" | threads) || fail "the run with $bind failed"
  [[ $got == "$want" ]] || fail "serial with $bind on $cpus CPUs: $got threads, not $want"
done
got=$(taskset -c 0 "$bin" "${problem[@]}" | threads) || fail "the run under taskset failed"
[[ $got == 1 ]] || fail "serial under taskset -c 0: $got threads, not 1"
echo "dense_threads_default: serial: $want thread(s) on $cpus CPUs, 1 under taskset -c 0"

# Under AddressSanitizer, memory errors but not leaks: Open MPI's components leak at start-up
# and are unloaded before LeakSanitizer reports (tests/mpi/CMakeLists.txt says more).
[[ -z ${ASAN_OPTIONS:-} ]] || export ASAN_OPTIONS=$ASAN_OPTIONS:detect_leaks=0
# Two ranks bound to a core each: one thread each, whatever the machine has.
out=$("$mpirun" -np 2 --bind-to core "$bin" "${problem[@]}") || fail "mpirun --bind-to core failed"
got=$(threads <<<"$out")
[[ $got == 1 ]] || fail "2 ranks bound to a core each: $got threads per rank, not 1"
# Two unbound ranks share this process's set: half of it each (at least 1, at most 3).
out=$("$mpirun" -np 2 --bind-to none "$bin" "${problem[@]}") || fail "mpirun --bind-to none failed"
got=$(threads <<<"$out")
want=$((cpus / 2)); ((want < 1)) && want=1; ((want > 3)) && want=3
[[ $got == "$want" ]] || fail "2 unbound ranks on $cpus CPUs: $got threads per rank, not $want"
echo "dense_threads_default: mpirun -np 2: 1 thread per rank bound to a core, $want unbound"
