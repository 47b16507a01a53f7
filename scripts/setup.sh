#!/usr/bin/env bash
# Installs the Debian packages hpcplan needs. Idempotent and quick when all are present:
# apt is only touched if something is missing. Needs root (or sudo) when it installs.
#
# --with-cuda: also a CUDA compiler for the fluid's GPU backend, when none is there (nvcc on the
# PATH or in /usr/local/cuda/bin): Debian's nvidia-cuda-toolkit (nvcc 11.8, which supports the
# H100's sm_90) with nvidia-cuda-toolkit-gcc (g++-11, the newest host compiler nvcc 11.8 takes).
# Both live in Debian's non-free component, which this option enables for bookworm in
# /etc/apt/sources.list.d/hpcplan-cuda.sources; without the option apt's sources are never
# touched. About 1.6 GB; measured at 120 s on a fresh VM (apt-get update included).
set -euo pipefail

with_cuda=0
for arg in "$@"; do
  case $arg in
    --with-cuda) with_cuda=1 ;;
    *) echo "setup: unknown option $arg (expected --with-cuda)" >&2; exit 2 ;;
  esac
done

SUDO=""
if [[ $(id -u) -ne 0 ]] && command -v sudo >/dev/null; then SUDO=sudo; fi

PACKAGES=(
  build-essential cmake ninja-build pkg-config python3
  libgtest-dev libgmock-dev libbenchmark-dev
  libabsl-dev nlohmann-json3-dev libcli11-dev robin-map-dev
  libopenmpi-dev openmpi-bin procps
  libompl-dev ompl-demos python3-matplotlib libnanoflann-dev
  python3-vtk9 ffmpeg
  python3-dev python3-numpy pybind11-dev python3-pybind11 python3-pytest
  slurm-wlm munge
  clang libomp-dev libclang-rt-dev time
)

if ((with_cuda)) && ! command -v nvcc >/dev/null && [[ ! -x /usr/local/cuda/bin/nvcc ]]; then
  PACKAGES+=(nvidia-cuda-toolkit nvidia-cuda-toolkit-gcc)
  if ! apt-cache policy nvidia-cuda-toolkit 2>/dev/null | grep -q Candidate: ||
    apt-cache policy nvidia-cuda-toolkit | grep -q "Candidate: (none)"; then
    src=/etc/apt/sources.list.d/hpcplan-cuda.sources
    echo "setup: enabling Debian's contrib and non-free components for CUDA ($src)"
    printf '%s\n' "Types: deb" "URIs: http://deb.debian.org/debian" "Suites: bookworm" \
      "Components: contrib non-free" \
      "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg" |
      $SUDO tee "$src" >/dev/null
  fi
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

if [[ $(id -u) -ne 0 && -z $SUDO ]]; then
  echo "setup: need root to install: ${missing[*]}" >&2
  exit 1
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
