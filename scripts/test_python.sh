#!/usr/bin/env bash
# The PyMeshLab route, as a user takes it: `pip install .` into the venv of scripts/setup.sh
# --pymeshlab (PyMeshLab 2025.7 from PyPI), then the tests of tests/python against the real wheel.
# With a MeshLab 2020.09 build (GROWTH_BUILD_DIR, default build/, with build/plugins/), the same
# clouds also go through meshlabserver and the face counts are compared; GROWTH_REQUIRE_MESHLAB2020=1
# makes a missing 2020.09 build a failure instead of a skip.
# Usage: scripts/test_python.sh [--sdist] [pytest arguments]
#   --sdist   build an sdist first and install from it (its build fetches the MeshLab 2025.07
#             headers from Debian's archive, checksum-pinned), instead of installing the tree
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$(pwd)
venv="$root/third_party/venv"
[ -x "$venv/bin/python" ] || { echo "test_python.sh: no venv: run scripts/setup.sh --pymeshlab" >&2; exit 1; }
sdist=0
if [ "${1:-}" = "--sdist" ]; then sdist=1; shift; fi
export GROWTH_BUILD_DIR=${GROWTH_BUILD_DIR:-$root/build}
export GROWTH_SOURCE_DIR=$root
export CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}
t0=$SECONDS
if [ $sdist -eq 1 ]; then
  dist=$(mktemp -d)
  trap 'rm -rf "$dist"' EXIT
  "$venv/bin/python" -m pip install -q --disable-pip-version-check build
  "$venv/bin/python" -m build --sdist --outdir "$dist" . >"$dist/sdist.log" 2>&1 || { cat "$dist/sdist.log"; exit 1; }
  target=$(ls "$dist"/growth_meshers-*.tar.gz)
  # The sdist carries no MeshLab or vcglib source: its build fetches them.
  if tar -tzf "$target" | grep -qE '(^|/)(vcglib|third_party)/'; then
    echo "test_python.sh: the sdist carries MeshLab sources" >&2; exit 1; fi
else
  target=.
fi
"$venv/bin/python" -m pip install -q --disable-pip-version-check --force-reinstall --no-deps "$target"
echo "test_python.sh: pip install $( [ $sdist -eq 1 ] && basename "$target" || echo . ) took $((SECONDS - t0)) s"
cd "$(mktemp -d)" # not the source tree, so that `import growth_meshers` is the installed package
"$venv/bin/python" -m pytest -q -p no:cacheprovider "$root/tests/python" "$@"
