#!/usr/bin/env bash
# cmake --install into a temporary prefix, then build and run an outside project against it
# with find_package(hpcplan): exported targets, their dependencies, headers of every layer.
set -euo pipefail
src=$1
build=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log"
for layer in core env search graph tree sampling plan partition mpi distributed io; do
  [[ -d "$tmp/prefix/include/hpcplan/$layer" ]] || { echo "FAIL: no headers of $layer installed" >&2; exit 1; }
done
cmake -S "$src/tests/package/consumer" -B "$tmp/consumer" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$tmp/consumer" >/dev/null
out=$("$tmp/consumer/consumer")
echo "$out"
[[ $out == "box map: solved "*"; lattice: solved "*"; launched by MPI: 0; fluid: ok" ]] || { echo "FAIL: $out" >&2; exit 1; }
# The Python package, where the install says it put it, imported by Debian's python3 from there.
pydir=$(sed -n 's/^HPCPLAN_PYTHON_INSTALL_DIR:STRING=//p' "$build/CMakeCache.txt")
if [[ -n $pydir ]]; then
  grep -q "the Python package is in $tmp/prefix/$pydir" "$tmp/install.log" ||
    { echo "FAIL: the install does not say where the Python package is" >&2; exit 1; }
  out=$(cd "$tmp" && PYTHONPATH="$tmp/prefix/$pydir" /usr/bin/python3 -c '
import hpcplan
assert hpcplan.__file__.startswith(__import__("sys").argv[1]), hpcplan.__file__
r = hpcplan.grid.solve(dims=3, extent=30, path=True)
print("python:", r.status, len(r.path))' "$tmp/prefix/$pydir")
  echo "$out"
  [[ $out == "python: solved "* ]] || { echo "FAIL: the installed Python package: $out" >&2; exit 1; }
fi
echo "package: installed, found and used"
