# Sourced by the tests, the demo and the benchmark: a scratch MeshLab prefix that loads our plugins.
#
#   make_meshlab_prefix <build-dir> <prefix-dir>
#     <prefix>/bin/meshlabserver                       a copy of Debian's binary
#     <prefix>/lib/x86_64-linux-gnu/meshlab/           libmeshlab-common.so (link)
#     <prefix>/lib/x86_64-linux-gnu/meshlab/plugins/   links to the system plugins and to ours
#   Debian's meshlabserver looks for plugins at <dir of the binary>/../lib/x86_64-linux-gnu/meshlab/
#   plugins, so the copy loads the freshly built plugins and the system stays untouched.
#
#   run_meshlabserver <prefix-dir> <args...>   runs it under xvfb-run (it needs a display)

: "${MESHLAB_SYSTEM_PLUGINS:=/usr/lib/x86_64-linux-gnu/meshlab/plugins}"
: "${MESHLABSERVER:=/usr/bin/meshlabserver}"

make_meshlab_prefix() {
  local build=$1 prefix=$2
  local libdir="$prefix/lib/x86_64-linux-gnu/meshlab"
  rm -rf "$prefix"
  mkdir -p "$prefix/bin" "$libdir/plugins"
  cp "$MESHLABSERVER" "$prefix/bin/meshlabserver"
  ln -s "$(dirname "$MESHLAB_SYSTEM_PLUGINS")/libmeshlab-common.so" "$libdir/libmeshlab-common.so"
  local p
  for p in "$MESHLAB_SYSTEM_PLUGINS"/*.so; do ln -s "$p" "$libdir/plugins/"; done
  for p in "$build"/plugins/*.so; do ln -sf "$(cd "$(dirname "$p")" && pwd)/$(basename "$p")" "$libdir/plugins/"; done
}

run_meshlabserver() {
  local prefix=$1; shift
  xvfb-run -a "$prefix/bin/meshlabserver" "$@"
}

# Counts from a PLY header.
ply_faces() { LC_ALL=C sed -n '/^end_header/q;s/^element face \([0-9]*\)/\1/p' "$1" | head -1; }
ply_vertices() { LC_ALL=C sed -n '/^end_header/q;s/^element vertex \([0-9]*\)/\1/p' "$1" | head -1; }
