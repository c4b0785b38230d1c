#!/usr/bin/env bash
# The sphere packer inside MeshLab: a generated cloud meshed by meshlabserver through the example
# script scripts/mlx/spherepack.mlx (automatic d and s); the result is a closed, manifold,
# consistently oriented mesh with per-face quality, every edge at least the d the filter logs.
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 10000 --seed 2 -o "$work/cloud.ply" >/dev/null
cp "$GROWTH_SOURCE_DIR/scripts/mlx/spherepack.mlx" "$work/spherepack.mlx"
mlserver -i cloud.ply -o mesh.ply -m vn fq -s spherepack.mlx > "$work/server.log" 2>&1 \
  || { cat "$work/server.log"; fail "meshlabserver failed"; }
[ -f "$work/mesh.ply" ] || { cat "$work/server.log"; fail "no mesh saved"; }
grep -q "Sphere Packing: time [0-9.]* s" "$work/server.log" || fail "no time in the filter's log"
d=$(sed -n 's/.*Sphere Packing: .* d = \([0-9.eE+-]*\),.*/\1/p' "$work/server.log" | head -1)
[ -n "$d" ] || fail "no d in the filter's log"
LC_ALL=C sed -n '/^end_header/q;p' "$work/mesh.ply" | grep -q "property float quality" \
  || fail "the saved mesh has no per-face quality"

"$GROWTH_BUILD_DIR/mesh_measures" "$work/mesh.ply" > "$work/measures.json" || fail "mesh_measures failed"
python3 - "$work/measures.json" "$d" <<'PY'
import json, sys
m, d = json.load(open(sys.argv[1])), float(sys.argv[2])
checks = [
    ("faces > 1500", m["faces"] > 1500),
    ("no boundary edges (closed)", m["boundary_edges"] == 0),
    ("no non-manifold edges", m["non_manifold_edges"] == 0),
    ("no non-manifold vertices", m["non_manifold_vertices"] == 0),
    ("consistently oriented", m["inconsistent_edges"] == 0),
    ("a sphere (Euler characteristic 2)", m["euler_characteristic"] == 2),
    ("no unreferenced vertices", m["unreferenced_vertices"] == 0),
    ("every edge >= d (float storage)", m["edge_min"] >= d * (1 - 1e-5)),
    ("every vertex pair >= d", m["min_vertex_distance"] >= d * (1 - 1e-5)),
    ("Q_avg >= 0.94", m["quality_mean"] >= 0.94),
    ("E_RMS <= 16 %", m["edge_rms_percent"] <= 16),
]
bad = [name for name, ok in checks if not ok]
if bad:
    print("FAIL: " + "; ".join(bad) + "\n" + json.dumps(m, indent=1))
    sys.exit(1)
print("ok: %d faces, Q_avg %.4f, E_RMS %.1f %%, smallest edge %.6g >= d = %.6g"
      % (m["faces"], m["quality_mean"], m["edge_rms_percent"], m["edge_min"], d))
PY
