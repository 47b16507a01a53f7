#!/usr/bin/env bash
# cmake --install into a temporary prefix, then build and run an outside project against it
# with find_package(hpcplan): exported targets, their dependencies, headers of every layer.
set -euo pipefail
src=$1
build=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
for layer in core env search graph tree sampling plan partition mpi distributed io; do
  [[ -d "$tmp/prefix/include/hpcplan/$layer" ]] || { echo "FAIL: no headers of $layer installed" >&2; exit 1; }
done
cmake -S "$src/tests/package/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$tmp/consumer" >/dev/null
out=$("$tmp/consumer/consumer")
echo "$out"
[[ $out == "box map: solved "*"; lattice: solved "*"; launched by MPI: 0; fluid: ok" ]] || { echo "FAIL: $out" >&2; exit 1; }
echo "package: installed, found and used"
