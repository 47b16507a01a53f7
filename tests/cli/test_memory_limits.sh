#!/usr/bin/env bash
# The memory limits for real (README "hpcplan grid", Budget and Engines; "hpcplan sph" and
# "hpcplan sim", bad input; cli/src/main.cpp).
#   budget: the default budgets are half of the available memory (MemAvailable in
#     /proc/meminfo): the grid's --max-states (the sparse engine stops with budget_exceeded,
#     exit 0) and what it buys the dense engine (--memory-budget: over it, --engine dense is
#     exit 2 naming the bytes, --engine auto runs the sparse engine), and the fluid's and the
#     simulator's --memory-mb (over it: exit 2, one line, nothing written). Checked against
#     this machine's /proc/meminfo, then exactly with a /proc/meminfo that reports 64 MiB
#     (bind-mounted in a private mount namespace: root only).
#   oom: the out-of-memory exit. Under an address-space limit (ulimit -v) an allocation fails
#     for real, in the sparse search as it grows, the dense engine's lattice, the fluid and the
#     simulator: each ends with exit 1 and exactly the one line "hpcplan: error: out of
#     memory; ...", nothing on stdout, no crash, an earlier --output intact and no file
#     written. Then the default budget's purpose: with the available memory reported as the
#     limit itself (256 MiB), the same search ends with budget_exceeded (exit 0), while
#     with the budget lifted it runs out of memory. Not in sanitizer builds: ASan and TSan
#     reserve terabytes of shadow memory, so no address-space limit lets them start.
# Whatever needs root (the bind mount) is skipped with its reason (exit 77) when not run as
# root, after everything else has run; as root (the test command in CI) it must work.
# Usage: test_memory_limits.sh HPCPLAN budget|oom
set -uo pipefail
bin=$(realpath "$1") mode=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() { echo "memory_limits ($mode): FAIL: $*" >&2; exit 1; }
note() { echo "memory_limits ($mode): $*"; }
needs_root=()  # what could not be checked without root

# run [-a KIB] [-v KIB] ARGS...: hpcplan ARGS with /proc/meminfo reporting MemAvailable KIB
# (-a) and an address-space limit of KIB (-v); sets rc, out, err.
can_fake=
if unshare --mount --propagation private true 2>/dev/null; then can_fake=1; fi
run() {
  local avail='' limit=''
  while [[ $1 == -a || $1 == -v ]]; do
    [[ $1 == -a ]] && avail=$2 || limit=$2
    shift 2
  done
  local cmd=("$bin" "$@")
  if [[ -n $avail ]]; then
    # MemTotal and MemFree differ from MemAvailable, so reading either instead shows.
    printf 'MemTotal: %d kB\nMemFree: %d kB\nMemAvailable: %d kB\n' "$((4 * avail))" \
      "$((avail / 2))" "$avail" > "$work/meminfo"
    # shellcheck disable=SC2016  # $1 and $@ are the inner shell's
    cmd=(unshare --mount --propagation private bash -c \
      'mount --bind "$1" /proc/meminfo && shift && exec "$@"' _ "$work/meminfo" "${cmd[@]}")
  fi
  if [[ -n $limit ]]; then
    out=$(ulimit -v "$limit" && "${cmd[@]}" 2> "$work/err")
  else
    out=$("${cmd[@]}" 2> "$work/err")
  fi
  rc=$?
  err=$(< "$work/err")
}
one_line() {  # one_line WHAT CODE PATTERN: exit CODE, one stderr line matching PATTERN, no stdout
  [[ $rc -eq $2 ]] || fail "$1: exit $rc, not $2 ($err)"
  # shellcheck disable=SC2053  # $3 is a glob pattern
  [[ $(wc -l <<< "$err") -eq 1 && $err == $3 ]] || fail "$1: stderr is not one line '$3': $err"
  [[ -z $out ]] || fail "$1: printed on stdout: $out"
}
available_kib() {
  local kib
  kib=$(awk '$1 == "MemAvailable:" { print $2 }' /proc/meminfo)
  [[ -n $kib ]] || fail "no MemAvailable in /proc/meminfo"
  echo "$kib"
}
json() { python3 -c 'import json, sys; print(json.loads(sys.argv[1])[sys.argv[2]])' "$out" "$1"; }
no_files() {  # no_files WHAT: nothing but the files listed in $work/keep exists under $work
  local made
  made=$(find . -type f ! -name err ! -name meminfo ! -name keep | grep -vxFf "$work/keep")
  [[ -z $made ]] || fail "$1: files written: $made"
}
: > keep

budget() {
  # --- This machine's /proc/meminfo (any user) ---
  local half_mib lo hi
  half_mib=$(($(available_kib) / 2048))
  if ((half_mib > 100 << 10)); then
    # The largest fluid allowed (200M particles, about 130 GiB) would fit: it would run.
    note "MemAvailable is over 200 GiB: the default budgets are checked with 64 MiB only"
    fake_only
    return
  fi
  # Other programs allocate and free while this runs: MemAvailable is read before and after
  # each run, and hpcplan's half of it must lie between half the smaller and half the larger,
  # give or take 10%.
  measured() {  # measured ARGS...: run ARGS between two reads of MemAvailable (lo, hi in MiB)
    local before after
    before=$(available_kib)
    run "$@"
    after=$(available_kib)
    lo=$(((before < after ? before : after) / 2048))
    hi=$(((before > after ? before : after) / 2048))
    half_mib=$(((lo + hi) / 2))
  }
  near_half() { (($1 >= lo * 9 / 10 && $1 <= hi * 11 / 10)); }
  measured sph --particles 200000000 --frames 1
  one_line "sph over the default budget" 2 "hpcplan: error: --particles 200000000 needs about * MiB, over the budget of * MiB (--memory-mb)"
  local got=${err##*over the budget of }
  got=${got%% MiB*}
  near_half "$got" || fail "sph's default budget is $got MiB, not half of MemAvailable (here $lo to $hi MiB)"
  measured sim --particles 200000000 --runs 1
  one_line "sim over the default budget" 2 "hpcplan: error: --particles 200000000 needs about * MiB for the fluid, over the budget of * MiB (--memory-mb)"
  got=${err##*over the budget of }
  got=${got%% MiB*}
  near_half "$got" || fail "sim's default budget is $got MiB, not half of MemAvailable (here $lo to $hi MiB)"
  # The dense engine's default budget is what the default --max-states buys the sparse engine:
  # bytes a state (from a budget of 1000 states) times the default state count.
  run grid --dims 4 --extent 5000 --algo bfs --engine dense --max-states 1000
  one_line "grid --engine dense over 1000 states" 2 "*over the budget of * bytes); raise --memory-budget*"
  local per_state=${err##*over the budget of * (}
  per_state=$((${per_state%% bytes*} / 1000))
  measured grid --dims 4 --extent 5000 --algo bfs --engine dense
  one_line "grid --engine dense over the default budget" 2 "*over the budget of * bytes); raise --memory-budget*"
  local bytes=${err##*over the budget of * (}
  bytes=${bytes%% bytes*}
  near_half $((bytes >> 20)) ||
    fail "the dense engine's default budget is $bytes bytes, not half of MemAvailable (here $lo to $hi MiB)"
  measured grid --dims 2 --extent 50 --algo astar --json
  [[ $rc -eq 0 ]] || fail "grid --algo astar: exit $rc ($err)"
  local states
  states=$(json max_states)
  near_half $((states * per_state >> 20)) ||
    fail "the default --max-states is $states states of $per_state bytes, not half of MemAvailable (here $lo to $hi MiB)"
  note "this machine: half of MemAvailable is $half_mib MiB; sph, sim, dense ($bytes bytes) and --max-states ($states states of $per_state bytes) agree"
  fake_only
}

fake_only() {
  # --- Exactly, with 64 MiB available (root) ---
  if [[ -z $can_fake ]]; then
    needs_root+=("the default budgets with a /proc/meminfo of 64 MiB")
    return
  fi
  local budget=$((32 << 20)) bytes states per_state
  run -a 65536 grid --dims 4 --extent 5000 --algo bfs --engine dense --max-states 1000
  per_state=${err##*over the budget of * (}
  per_state=$((${per_state%% bytes*} / 1000))
  run -a 65536 sph --particles 100000 --frames 1 --vtk vtk --json --output o.json --checkpoint ck
  one_line "sph, 64 MiB available" 2 "hpcplan: error: --particles 100000 needs about * MiB, over the budget of 32 MiB (--memory-mb)"
  [[ ! -e vtk ]] || fail "sph over the budget created vtk/"
  no_files "sph over the budget"
  run -a 65536 sph --particles 1000 --frames 1 --json
  [[ $rc -eq 0 ]] || fail "sph --particles 1000 refused with 64 MiB available: exit $rc ($err)"
  run -a 65536 sim --particles 100000 --runs 1 --trajectory t.csv --json
  one_line "sim, 64 MiB available" 2 "hpcplan: error: --particles 100000 needs about * MiB for the fluid, over the budget of 32 MiB (--memory-mb)"
  no_files "sim over the budget"
  # A 3D BFS over 700^3 states: the dense engine needs 97 MB, over the 32 MiB; the sparse
  # engine stores states up to the budget and stops there.
  run -a 65536 grid --dims 3 --extent 700 --algo bfs --engine dense
  one_line "grid --engine dense, 64 MiB available" 2 "*over the budget of * bytes); raise --memory-budget*"
  bytes=${err##*over the budget of * (}
  bytes=${bytes%% bytes*}
  ((bytes <= budget && bytes > budget - per_state)) ||
    fail "the dense engine's budget is $bytes bytes with 64 MiB available, not 32 MiB in whole states"
  run -a 65536 grid --dims 3 --extent 700 --algo bfs --json
  [[ $rc -eq 0 ]] || fail "grid --algo bfs, 64 MiB available: exit $rc ($err)"
  [[ $(json engine) == sparse && $(json status) == budget_exceeded ]] ||
    fail "grid --algo bfs over the dense budget: engine $(json engine), status $(json status)"
  states=$(json max_states)
  ((states == budget / per_state)) ||
    fail "max_states $states with 64 MiB available, not $((budget / per_state)) (32 MiB of $per_state bytes)"
  (($(json peak_states) <= states + 1)) || fail "stored $(json peak_states) states over a budget of $states"
  run -a 65536 grid --dims 3 --extent 200 --algo bfs --json
  [[ $rc -eq 0 && $(json engine) == dense && $(json status) == solved ]] ||
    fail "grid --algo bfs within the dense budget: exit $rc, $out $err"
  note "64 MiB available: sph, sim and grid --engine dense refused in one line, nothing written; the sparse engine stopped at $states states; a lattice that fits ran dense"
}

oom() {
  local limit=$((256 << 10)) message="hpcplan: error: out of memory; lower the problem size (*)"
  echo '{"earlier": true}' > o.json
  echo ./o.json >> keep
  # The sparse engine's visited map grows until an allocation fails (about 2.5M states).
  run -v "$limit" grid --dims 3 --extent 700 --algo bfs --engine sparse --max-states 100000000 \
    --json --output o.json
  one_line "grid --engine sparse out of memory" 1 "$message"
  [[ $(< o.json) == '{"earlier": true}' ]] || fail "grid out of memory changed o.json: $(< o.json)"
  no_files "grid --engine sparse out of memory"
  # The dense engine's lattice (430 MB) under a budget raised past the limit.
  run -v "$limit" grid --dims 3 --extent 1200 --algo bfs --engine dense \
    --memory-budget 100000000000 --threads 2 --json --output o.json --checkpoint ck
  one_line "grid --engine dense out of memory" 1 "$message"
  [[ $(< o.json) == '{"earlier": true}' ]] || fail "dense out of memory changed o.json: $(< o.json)"
  no_files "grid --engine dense out of memory"
  # The fluid and the simulator, with --memory-mb raised past the limit.
  run -v "$limit" sph --particles 2000000 --memory-mb 100000 --frames 2 --threads 2 --vtk vtk \
    --json --output o.json --checkpoint ck
  one_line "sph out of memory" 1 "$message"
  [[ $(< o.json) == '{"earlier": true}' ]] || fail "sph out of memory changed o.json: $(< o.json)"
  no_files "sph out of memory"
  run -v "$limit" sim --particles 2000000 --memory-mb 100000 --runs 1 --max-sim-s 1 --threads 2 \
    --trajectory t.csv --checkpoint ck --json --output o.json
  one_line "sim out of memory" 1 "$message"
  [[ $(< o.json) == '{"earlier": true}' ]] || fail "sim out of memory changed o.json: $(< o.json)"
  no_files "sim out of memory"
  note "under ulimit -v $limit: the sparse search, the dense lattice, the fluid and the simulator each ended with exit 1 and '$err'; nothing written"

  # The default budget under the same limit, with the limit reported as the available memory.
  if [[ -z $can_fake ]]; then
    needs_root+=("the default budget under an address-space limit reported as MemAvailable")
    return
  fi
  run -a "$limit" -v "$limit" grid --dims 3 --extent 700 --algo bfs --engine sparse --json
  [[ $rc -eq 0 ]] || fail "the default budget under ulimit -v $limit with as much available: exit $rc ($err)"
  [[ $(json status) == budget_exceeded ]] || fail "the default budget: status $(json status)"
  note "the default budget under the same limit: budget_exceeded at $(json max_states) states, exit 0"
}

case $mode in
  budget) budget ;;
  oom) oom ;;
  *) fail "unknown mode $mode" ;;
esac
if ((${#needs_root[@]})); then
  printf -v what '%s; ' "${needs_root[@]}"
  if [[ $(id -u) -eq 0 ]]; then
    fail "running as root, yet cannot bind-mount a /proc/meminfo in a private mount namespace (unshare --mount): ${what%; }"
  fi
  echo "memory_limits ($mode): SKIPPED: user $(id -un) cannot bind-mount /proc/meminfo (needs root), so not checked: ${what%; }"
  exit 77
fi
note ok
