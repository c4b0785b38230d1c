#!/usr/bin/env bash
# mesh_measures reads a double PLY (as PyMeshLab and the double MeshLab builds save) as stored: two
# triangles near x = 1 sharing an edge 1e-9 long. Rounded to float (steps of 2^-23 there) the edge
# would vanish; in double the shortest edge is 1e-9. The same mesh saved in float has a shortest
# edge of 0, so the check can fail.
set -euo pipefail
: "${GROWTH_BUILD_DIR:?set by ctest}"
fail() { echo "FAIL: $*" >&2; exit 1; }
work="$GROWTH_BUILD_DIR/integration/$(basename "$0" .sh)"
rm -rf "$work" && mkdir -p "$work"

python3 - "$work" <<'PY'
import struct, sys
work = sys.argv[1]
v = [(1.0, 0.0, 0.0), (1.0 + 1e-9, 0.0, 0.0), (1.0, 1.0, 0.0), (1.0, -1.0, 0.0)]
f = [(0, 1, 2), (1, 0, 3)]
for kind, fmt in (("double", "<3d"), ("float", "<3f")):
    with open("%s/%s.ply" % (work, kind), "wb") as out:
        out.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty %s x\nproperty %s y\n"
                   "property %s z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                   % (len(v), kind, kind, kind, len(f))).encode())
        for p in v:
            out.write(struct.pack(fmt, *p))
        for t in f:
            out.write(struct.pack("<B3i", 3, *t))
PY
value() { sed -n "s/^ *\"$1\": \([0-9.eE+-]*\),*$/\1/p" "$2"; }
"$GROWTH_BUILD_DIR/mesh_measures" "$work/double.ply" > "$work/double.json" || fail "mesh_measures failed"
"$GROWTH_BUILD_DIR/mesh_measures" "$work/float.ply" > "$work/float.json" || fail "mesh_measures failed on float"
python3 - "$(value edge_min "$work/double.json")" "$(value edge_min "$work/float.json")" <<'PY' \
  || fail "the double PLY was not measured as stored"
import sys
edge_min, edge_min_float = float(sys.argv[1]), float(sys.argv[2])
assert abs(edge_min - 1e-9) < 1e-15, edge_min
assert edge_min_float == 0, edge_min_float
PY
echo "ok: a double PLY is measured in double (shortest edge 1e-9; 0 in float)"
