# Sourced by the sbatch templates: locates the build, sets Open MPI's root variables, makes
# the job's own result folder results/<study>/<job id>[.<n>] with meta.json (options, git
# revision, node list), so reruns never overwrite each other while a requeued job finds its
# own folder again, and runs the job's long steps so that SLURM's warning before the time
# limit (#SBATCH --signal=B:USR1@SECONDS) ends them at a checkpoint and requeues the job
# (hpcplan_step; slurm/README.md explains the whole path).
# Environment: HPCPLAN_ROOT (repository; default: where the job was submitted),
#              HPCPLAN_BIN_DIR (default: $HPCPLAN_ROOT/build/bin),
#              HPCPLAN_RESULTS (default: $HPCPLAN_ROOT/results),
#              HPCPLAN_RESUME_DIR (a result folder of an earlier job of the same study and
#                options to continue in, e.g. after it was cancelled or ran past its limit),
#              MAX_REQUEUES (20: how many times a job may requeue itself).
set -euo pipefail
HPCPLAN_ROOT=${HPCPLAN_ROOT:-${SLURM_SUBMIT_DIR:-$PWD}}
HPCPLAN_BIN_DIR=${HPCPLAN_BIN_DIR:-$HPCPLAN_ROOT/build/bin}
HPCPLAN_RESULTS=${HPCPLAN_RESULTS:-$HPCPLAN_ROOT/results}
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi

hpcplan_die() {
  echo "hpcplan job: error: $*" >&2
  exit 2
}

hpcplan_bin() {
  local b=$HPCPLAN_BIN_DIR/$1
  [[ -x $b ]] || hpcplan_die "$b not found: build first (bash scripts/build.sh) or set HPCPLAN_BIN_DIR"
  echo "$b"
}

# The job's name in result folders: <job id>, or <array job id>_<task> for an array task; both
# stay the same when SLURM requeues the job.
_hpcplan_job_name() {
  local id=${SLURM_ARRAY_JOB_ID:+${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}}
  echo "${id:-${SLURM_JOB_ID:-local-$$}}"
}

# hpcplan_results_dir STUDY [KEY=VALUE ...]: creates and prints the job's result folder. A new
# job gets a folder of its own, never an earlier job's (<id>.<n> when <id> exists, as when a
# cluster reuses job ids). A requeued job (SLURM_RESTART_COUNT > 0, or the folder holds the
# marker hpcplan_requeue left for this job id) gets the folder it made before, with its
# checkpoints; HPCPLAN_RESUME_DIR names one explicitly (same study and options).
hpcplan_results_dir() {
  local study=$1
  shift
  local id dir=""
  id=$(_hpcplan_job_name)
  mkdir -p "$HPCPLAN_RESULTS/$study" || hpcplan_die "cannot create $HPCPLAN_RESULTS/$study"
  if [[ -n ${HPCPLAN_RESUME_DIR:-} ]]; then
    dir=$HPCPLAN_RESUME_DIR
    [[ -f $dir/meta.json ]] || hpcplan_die "HPCPLAN_RESUME_DIR=$dir is not a result folder (no meta.json)"
  elif [[ -n ${SLURM_JOB_ID:-} ]]; then
    dir=$(_hpcplan_meta find "$HPCPLAN_RESULTS/$study" "$id")
  fi
  if [[ -z $dir ]]; then
    dir=$HPCPLAN_RESULTS/$study/$id
    local n=1
    while ! mkdir "$dir" 2>/dev/null; do
      dir=$HPCPLAN_RESULTS/$study/$id.$n
      n=$((n + 1))
      ((n < 1000)) || hpcplan_die "cannot create a result folder under $HPCPLAN_RESULTS/$study"
    done
  else
    echo "hpcplan job: restart ${SLURM_RESTART_COUNT:-0} of job ${SLURM_JOB_ID:-local}: continuing in $dir" >&2
  fi
  local rev
  rev=$(git -C "$HPCPLAN_ROOT" rev-parse HEAD 2>/dev/null || echo unknown)
  _hpcplan_meta write "$dir" "$study" "$rev" "$@" || exit 2
  rm -f "$dir/.requeued.$id"
  echo "$dir"
}

# _hpcplan_meta find ROOT ID: prints the folder under ROOT this job made before it was requeued
# (the newest <ID> or <ID>.<n> whose meta.json names this job), if this is a requeued run.
# _hpcplan_meta write DIR STUDY REV [KEY=VALUE ...]: writes DIR/meta.json, or, for a folder made
# by an earlier run, checks that the study and options are the same and adds this run to "runs".
_hpcplan_meta() {
  python3 - "$@" <<'PY'
import datetime, glob, json, os, sys
env = os.environ.get
run = {
    "job_id": env("SLURM_JOB_ID"), "array_task": env("SLURM_ARRAY_TASK_ID"),
    "restart_count": int(env("SLURM_RESTART_COUNT") or 0),
    "nodelist": env("SLURM_JOB_NODELIST", os.uname().nodename),
    "started": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
}
def load(path):
    try:
        return json.load(open(path))
    except (OSError, ValueError):
        return None
if sys.argv[1] == "find":
    root, name = sys.argv[2:4]
    best = None
    for folder in [os.path.join(root, name)] + glob.glob(os.path.join(root, name + ".*")):
        meta = load(os.path.join(folder, "meta.json"))
        if meta is None:
            continue
        runs = meta.get("runs") or [meta]
        if not any(r.get("job_id") == run["job_id"] for r in runs):
            continue
        if run["restart_count"] == 0 and not os.path.exists(os.path.join(folder, ".requeued." + name)):
            continue  # the same id, another job (a cluster that reuses ids): never its folder
        last = max(r.get("started", "") for r in runs)
        if best is None or last > best[0]:
            best = (last, folder)
    print(best[1] if best else "")
    sys.exit(0)
path = os.path.join(sys.argv[2], "meta.json")
study, rev, *opts = sys.argv[3:]
options = dict(o.split("=", 1) for o in opts)
meta = load(path)
if meta is None:
    meta = {"study": study, "git_revision": rev, "job_id": run["job_id"],
            "array_task": run["array_task"], "nodelist": run["nodelist"],
            "ntasks": env("SLURM_NTASKS"), "cpus_on_node": env("SLURM_CPUS_ON_NODE"),
            "started": run["started"], "options": options, "runs": [run]}
else:
    if meta.get("study") != study or meta.get("options") != options:
        sys.exit(f"hpcplan job: error: {sys.argv[2]} holds {meta.get('study')} with options "
                 f"{meta.get('options')}, not {study} with {options}: it cannot be continued with these")
    meta.setdefault("runs", []).append(run)
    if rev != meta.get("git_revision"):
        run["git_revision"] = rev
tmp = path + ".tmp"
with open(tmp, "w") as f:
    json.dump(meta, f, indent=2)
os.replace(tmp, path)
PY
}

# hpcplan_powers_of_two N: "1 2 4 ... <= N".
hpcplan_powers_of_two() {
  local n=$1 p list=""
  for ((p = 1; p <= n; p *= 2)); do list+="$p "; done
  echo "$list"
}

# hpcplan_check_p_list "P ..." NTASKS: every P a positive integer no larger than the job.
hpcplan_check_p_list() {
  local p
  for p in $1; do
    [[ $p =~ ^[1-9][0-9]*$ ]] || hpcplan_die "P_LIST entry '$p' is not a positive integer"
    ((p <= $2)) || hpcplan_die "P = $p exceeds the job's $2 tasks (raise --ntasks or trim P_LIST)"
  done
}

# hpcplan_already_done STUDY CSV LABEL KEY=VALUE...: true when an earlier job of STUDY with
# these options wrote a row labelled LABEL (so a rerun study skips the points it has), unless
# SKIP_DONE=0.
hpcplan_already_done() {
  [[ ${SKIP_DONE:-1} == 1 ]] || return 1
  local study=$1 csv=$2 label=$3
  shift 3
  python3 - "$HPCPLAN_RESULTS/$study" "$csv" "$label" "$@" <<'PY'
import csv, glob, json, os, sys
root, name, label, *opts = sys.argv[1:]
want = dict(o.split("=", 1) for o in opts)
for meta_path in glob.glob(os.path.join(root, "*", "meta.json")):
    folder = os.path.dirname(meta_path)
    try:
        meta = json.load(open(meta_path))
    except (OSError, ValueError):
        continue
    if any(meta.get("options", {}).get(k) != v for k, v in want.items()):
        continue
    path = os.path.join(folder, name)
    if os.path.exists(path) and any(r.get("label") == label for r in csv.DictReader(open(path))):
        sys.exit(0)
sys.exit(1)
PY
}

# --- Checkpointed, requeueable steps ---------------------------------------------------------
# `#SBATCH --signal=B:USR1@SECONDS` sends SIGUSR1 to the batch shell alone, SECONDS (give or
# take a minute) before the time limit. Bash runs a trap only once the foreground command has
# ended, so hpcplan_step runs each step in the background and waits for it; its trap then:
#   - a step that saves (RESULT a JSON file or -): forwards one SIGUSR1 to it (mpirun forwards
#     SIGUSR1 to its ranks). The program ends at its next boundary (a frame, a level) with its
#     checkpoint written and says so: exit 0 and "status": "interrupted" in RESULT, or exit 75
#     (EX_TEMPFAIL) for a script step (RESULT -). The job then requeues itself (scontrol
#     requeue: same job id, same result folder, SLURM_RESTART_COUNT + 1) and its next run
#     passes --restart (hpcplan_restart_args).
#   - a step that cannot save (RESULT none): requeues the job at once; the next run starts that
#     step over and skips the finished ones (the scaling studies' "already measured"). Not when
#     no step finished in this run: that would loop; the job then runs on to its limit.
# SIGTERM or SIGINT (scancel, the time limit itself, Ctrl-C) never requeue: the step is asked
# to stop (one SIGUSR1, besides the SIGTERM SLURM sends it directly), its checkpoint is kept,
# and the job exits 143 once the step has ended (HPCPLAN_RESUME_DIR continues it).
_hpcplan_signal=""     # the first of USR1, TERM, INT this shell received
_hpcplan_stopping=0    # a TERM or INT came: the job ends, it is not requeued
_hpcplan_trapped=0     # a trap ran since the step's first wait began
_hpcplan_child=""      # the step running in the background
_hpcplan_forwarded=0   # the step has had its one SIGUSR1 (a second would end it: SA_RESETHAND)
_hpcplan_saves=1       # the step in progress writes a checkpoint when asked
_hpcplan_out=""        # the job's folder, for hpcplan_requeue's marker
_hpcplan_done_steps=0  # steps that ended in this run of the job

_hpcplan_on_signal() {  # the trap action; nothing in it may fail (set -e)
  [[ -n $_hpcplan_signal ]] || _hpcplan_signal=$1
  [[ $1 == USR1 ]] || _hpcplan_stopping=1
  _hpcplan_trapped=1
  [[ -n $_hpcplan_child ]] || return 0
  if ((_hpcplan_saves)); then
    if ((!_hpcplan_forwarded)); then
      _hpcplan_forwarded=1
      echo "hpcplan job: SIG$1: asking the step to stop at its next checkpoint" >&2 || true
      kill -USR1 "$_hpcplan_child" 2>/dev/null || true
    fi
  elif [[ $1 == USR1 ]]; then
    if ((_hpcplan_done_steps == 0)); then
      echo "hpcplan job: SIGUSR1, but no step ended in this run: requeueing would start the same" \
        "step over, so the job runs on to its time limit (give it more --time)" >&2 || true
    elif ((${SLURM_RESTART_COUNT:-0} >= ${MAX_REQUEUES:-20})); then
      echo "hpcplan job: SIGUSR1, but the job was requeued ${SLURM_RESTART_COUNT:-0} times already" \
        "(MAX_REQUEUES): it runs on to its time limit" >&2 || true
    else
      hpcplan_requeue "$_hpcplan_out" "SIGUSR1 during a step that keeps no checkpoint; it runs again"
    fi
  fi
  return 0
}

# _hpcplan_stop_child: ends the step still running (one that keeps no checkpoint) and waits for
# it, before the shell exits: a process left behind by the batch shell escapes SLURM's process
# tracking (proctrack/linuxproc), and would finish its measurement after the requeue.
_hpcplan_stop_child() {
  [[ -n $_hpcplan_child ]] || return 0
  kill -TERM "$_hpcplan_child" 2>/dev/null || true
  wait "$_hpcplan_child" 2>/dev/null || true
  _hpcplan_child=""
}
# From here on a warning signal is recorded, not fatal (bash's default for SIGUSR1): one that
# comes before the first step (a time limit shorter than the signal's lead) is reported there.
trap '_hpcplan_on_signal USR1' USR1

# _hpcplan_step_name CMD...: the program a step runs, for messages ("hpcplan under mpirun").
_hpcplan_step_name() {
  local a launcher=""
  for a in "$@"; do
    case $a in
      env | bash | sh | -* | *=*) ;;
      mpirun | mpiexec | srun) launcher=" under $a" ;;
      */*)
        echo "$(basename "$a")$launcher"
        return ;;
      *) if [[ -z $launcher ]]; then echo "$a"; return; fi ;;
    esac
  done
  basename "$1"
}

# hpcplan_step OUT RESULT CMD...: runs one step of the job (see above). OUT: the job's folder;
# RESULT: the step's JSON result file, - for a step that exits 75 when interrupted, or none for
# a step that cannot save. Returns when the step finished; exits when it failed (with its
# status), when it was interrupted (requeued), or after a SIGTERM/SIGINT (143).
hpcplan_step() {
  local out=$1 result=$2
  shift 2
  _hpcplan_out=$out _hpcplan_saves=1
  [[ $result != none ]] || _hpcplan_saves=0
  trap '_hpcplan_on_signal USR1' USR1
  trap '_hpcplan_on_signal TERM' TERM
  trap '_hpcplan_on_signal INT' INT
  local what
  what=$(_hpcplan_step_name "$@")
  if ((_hpcplan_stopping)); then
    echo "hpcplan job: stopped by SIG$_hpcplan_signal before $what began" >&2
    exit 143
  elif [[ -n $_hpcplan_signal ]]; then  # the warning came between two steps
    ((_hpcplan_done_steps > 0)) ||
      hpcplan_die "SIGUSR1 before the first step began: the time limit is shorter than the signal's lead"
    hpcplan_requeue "$out" "SIGUSR1 before $what began"
  fi
  [[ $result == - || $result == none ]] || rm -f "$result"  # an earlier run's, interrupted
  _hpcplan_trapped=0 _hpcplan_forwarded=0
  "$@" &
  _hpcplan_child=$!
  local rc=0 again
  wait "$_hpcplan_child" || rc=$?
  # A trap ends `wait` early (status 128 + signal): wait again for the step itself. Bash keeps
  # the status of a child it has reaped, and says 127 once it has none to give.
  while ((_hpcplan_trapped)); do
    _hpcplan_trapped=0 again=0
    wait "$_hpcplan_child" 2>/dev/null || again=$?
    ((again != 127)) || break
    rc=$again
  done
  _hpcplan_child=""
  if ((_hpcplan_stopping)); then
    echo "hpcplan job: stopped by SIG$_hpcplan_signal (scancel, or the time limit): $what exited" \
      "$rc; what it saved in $out is kept (continue with HPCPLAN_RESUME_DIR=$out)" >&2
    exit 143
  fi
  local interrupted=0
  if ((_hpcplan_saves)); then
    if [[ $result == - ]]; then
      ((rc != 75)) || interrupted=1
    elif ((rc == 0)) && [[ -f $result ]]; then
      python3 -c 'import json, sys; sys.exit(json.load(open(sys.argv[1])).get("status") != "interrupted")' \
        "$result" 2>/dev/null && interrupted=1
    fi
    # Asked before it had installed its handler (while setting up), a program ends at once,
    # with SIGUSR1's default action: its last checkpoint, if any, is still there.
    ((!_hpcplan_forwarded || rc != 138)) || interrupted=1
  fi
  if ((interrupted)); then
    hpcplan_requeue "$out" "$what stopped at a checkpoint"
  fi
  if ((rc != 0)); then
    echo "hpcplan job: error: $what failed (exit $rc)" >&2
    exit "$rc"
  fi
  _hpcplan_done_steps=$((_hpcplan_done_steps + 1))
}

# hpcplan_requeue OUT WHY: requeues this job (same id, same folder OUT) and exits, once the step
# still running, if any, has ended; outside SLURM exits 75 (run it again to continue). At most
# MAX_REQUEUES times.
hpcplan_requeue() {
  local out=$1 why=$2
  if [[ -z ${SLURM_JOB_ID:-} ]]; then
    echo "hpcplan job: $why; not under SLURM: run it again to continue" >&2
    _hpcplan_stop_child
    exit 75
  fi
  local n=${SLURM_RESTART_COUNT:-0} max=${MAX_REQUEUES:-20}
  ((n < max)) || hpcplan_die "$why; requeued $n times already (MAX_REQUEUES=$max): not again" \
    "(continue with HPCPLAN_RESUME_DIR=$out)"
  local marker=$out/.requeued.$(_hpcplan_job_name)
  [[ ! -f $out/meta.json ]] || : > "$marker"
  echo "hpcplan job: $why; requeueing job $SLURM_JOB_ID (restart $((n + 1)))" >&2
  # The requeue sends SIGTERM to every process of the job, scontrol included: it must not die
  # of it before it says that the requeue was done.
  if ! (trap '' TERM; exec scontrol requeue "$SLURM_JOB_ID"); then
    rm -f "$marker"
    if [[ -n $_hpcplan_child ]]; then  # (from the trap, during a step that keeps no checkpoint)
      echo "hpcplan job: scontrol requeue failed: the step runs on" >&2
      return 0
    fi
    hpcplan_die "scontrol requeue failed (a job submitted with --no-requeue?): continue with HPCPLAN_RESUME_DIR=$out"
  fi
  _hpcplan_stop_child
  exit 0
}

# hpcplan_restart_args CHECKPOINT [RANKS]: sets HPCPLAN_RESTART_ARGS to (--restart CHECKPOINT)
# when an earlier run of the job left it (on RANKS > 1: CHECKPOINT.r0 ... CHECKPOINT.r<RANKS-1>,
# one file per rank, all of them), else to nothing.
hpcplan_restart_args() {
  local ck=$1 ranks=${2:-1} have=0 r
  HPCPLAN_RESTART_ARGS=()
  if ((ranks == 1)); then
    [[ ! -f $ck ]] || have=1
  else
    for ((r = 0; r < ranks; r++)); do [[ ! -f $ck.r$r ]] || have=$((have + 1)); done
    ((have == 0 || have == ranks)) ||
      hpcplan_die "$have of the $ranks per-rank checkpoints $ck.r* are there: a restart needs them all (on as many ranks)"
  fi
  if ((have > 0)); then
    HPCPLAN_RESTART_ARGS=(--restart "$ck")
    echo "hpcplan job: restarting from $ck" >&2
  fi
}

# hpcplan_grid_checkpoint CHECKPOINT RANKS RESULT: the options and RESULT argument of a
# checkpointed `hpcplan grid` step: HPCPLAN_CK_ARGS=(--checkpoint CHECKPOINT [--restart ...])
# and HPCPLAN_CK_RESULT=RESULT.
hpcplan_grid_checkpoint() {
  local ck=$1 ranks=$2 result=$3
  hpcplan_restart_args "$ck" "$ranks"
  # shellcheck disable=SC2034  # read by the templates
  HPCPLAN_CK_ARGS=(--checkpoint "$ck" "${HPCPLAN_RESTART_ARGS[@]}")
  # shellcheck disable=SC2034
  HPCPLAN_CK_RESULT=$result
}
