# Sourced by the sbatch templates: locates the build, sets Open MPI's root variables, and makes
# the job's own result folder results/<study>/<job id>[.<n>] with meta.json (options, git
# revision, node list), so reruns and requeues never overwrite each other.
# Environment: HPCPLAN_ROOT (repository; default: where the job was submitted),
#              HPCPLAN_BIN_DIR (default: $HPCPLAN_ROOT/build/bin),
#              HPCPLAN_RESULTS (default: $HPCPLAN_ROOT/results).
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

# hpcplan_results_dir STUDY [KEY=VALUE ...]: creates and prints the job's result folder.
hpcplan_results_dir() {
  local study=$1
  shift
  local id=${SLURM_ARRAY_JOB_ID:+${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}}
  id=${id:-${SLURM_JOB_ID:-local-$$}}
  local dir=$HPCPLAN_RESULTS/$study/$id n=1
  while ! mkdir -p "$(dirname "$dir")" || ! mkdir "$dir" 2>/dev/null; do
    dir=$HPCPLAN_RESULTS/$study/$id.$n
    n=$((n + 1))
    ((n < 1000)) || hpcplan_die "cannot create a result folder under $HPCPLAN_RESULTS/$study"
  done
  local rev
  rev=$(git -C "$HPCPLAN_ROOT" rev-parse HEAD 2>/dev/null || echo unknown)
  python3 - "$dir/meta.json" "$study" "$rev" "$@" <<'PY'
import json, os, sys, datetime
path, study, rev, *opts = sys.argv[1:]
meta = {
    "study": study, "git_revision": rev,
    "job_id": os.environ.get("SLURM_JOB_ID"), "array_task": os.environ.get("SLURM_ARRAY_TASK_ID"),
    "nodelist": os.environ.get("SLURM_JOB_NODELIST", os.uname().nodename),
    "ntasks": os.environ.get("SLURM_NTASKS"), "cpus_on_node": os.environ.get("SLURM_CPUS_ON_NODE"),
    "started": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
    "options": dict(o.split("=", 1) for o in opts),
}
tmp = path + ".tmp"
with open(tmp, "w") as f:
    json.dump(meta, f, indent=2)
os.replace(tmp, path)
PY
  echo "$dir"
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
