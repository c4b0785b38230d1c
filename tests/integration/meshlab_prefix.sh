# Sourced by the integration tests: a scratch MeshLab prefix with our plugins (scripts/meshlab_env.sh)
# and a scratch folder for the test's files. Provides mlserver, fail, faces_of, vertices_of.
set -euo pipefail
: "${GROWTH_BUILD_DIR:?set by ctest}"
: "${GROWTH_SOURCE_DIR:?set by ctest}"
source "$GROWTH_SOURCE_DIR/scripts/meshlab_env.sh"

fail() { echo "FAIL: $*" >&2; exit 1; }

prefix="$GROWTH_BUILD_DIR/meshlab-prefix"
make_meshlab_prefix "$GROWTH_BUILD_DIR" "$prefix"

work="$GROWTH_BUILD_DIR/integration/$(basename "$0" .sh)"
rm -rf "$work" && mkdir -p "$work"

mlserver() { ( cd "$work" && run_meshlabserver "$prefix" "$@" ); }
faces_of() { ply_faces "$1"; }
vertices_of() { ply_vertices "$1"; }
