#!/usr/bin/env bash
# sbatch with the checks a user would otherwise learn from a failed job: a reachable SLURM
# controller, a built binary, and a template that exists. Everything after the template name
# goes to sbatch before it (options such as --ntasks, --array, --export).
# Usage: bash slurm/submit.sh TEMPLATE [sbatch options...]
#   e.g. P_LIST="1 2 4 8" bash slurm/submit.sh strong_scaling --ntasks 8
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
die() { echo "submit: error: $*" >&2; exit 2; }
[[ $# -ge 1 ]] || die "usage: submit.sh TEMPLATE [sbatch options...] (templates: $(cd "$here" && ls *.sbatch | sed 's/.sbatch//' | tr '\n' ' '))"
name=${1%.sbatch}
shift
template=$here/$name.sbatch
[[ -f $template ]] || die "no template slurm/$name.sbatch"
command -v sbatch >/dev/null || die "sbatch not found: not on a SLURM login node (or apt-get install slurm-wlm)"
# A SLURM_CONF that names no file: SLURM's tools retry reading it for a minute before failing.
[[ -z ${SLURM_CONF:-} || ( -f $SLURM_CONF && -r $SLURM_CONF ) ]] || die "SLURM_CONF=$SLURM_CONF is not a readable file"
timeout 30 scontrol ping >/dev/null 2>&1 || die "no SLURM controller answers (scontrol ping); start one with: eval \"\$(bash slurm/local_cluster.sh start)\""
bins=${HPCPLAN_BIN_DIR:-$root/build/bin}
[[ -x $bins/hpcplan ]] || die "$bins/hpcplan not found: build first (bash scripts/build.sh) or set HPCPLAN_BIN_DIR"
export HPCPLAN_ROOT=${HPCPLAN_ROOT:-$root}
exec sbatch "$@" "$template"
