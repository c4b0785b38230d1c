#!/usr/bin/env bash
# The sphere-packing remesher inside MeshLab: a torus mesh (the sphere packer's reconstruction of a
# generated cloud, through spherepack_run) remeshed by meshlabserver through the example script
# scripts/mlx/spherepack_remesh.mlx (automatic d = the mean edge length); the result is a closed,
# manifold, consistently oriented torus with per-face quality, every edge at least the d the filter
# logs. A point cloud given to the remesher fails with a clear message and no output.
source "$(dirname "$0")/meshlab_prefix.sh"
source "$(dirname "$0")/mesher_checks.sh"

"$GROWTH_BUILD_DIR/spherepack_run" --shape torus --points 20000 --seed 3 -o "$work/torus.ply" >/dev/null \
  || fail "spherepack_run could not make the input torus"
mlserver_mlx spherepack_remesh torus.ply remeshed.ply -m vn fq
grep -q "Sphere Packing remesh: time [0-9.]* s" "$work/server.log" || fail "no time in the filter's log"
d=$(sed -n 's/.*Sphere Packing remesh: sphere diameter d = \([0-9.eE+-]*\) .*/\1/p' "$work/server.log" | head -1)
[ -n "$d" ] || fail "no d in the filter's log"
LC_ALL=C sed -n '/^end_header/q;p' "$work/remeshed.ply" | grep -q "property float quality" \
  || fail "the saved mesh has no per-face quality"
"$GROWTH_BUILD_DIR/mesh_measures" "$work/remeshed.ply" --no-min-vertex-distance > "$work/remeshed.json" \
  || fail "mesh_measures failed"
python3 - "$work/remeshed.json" "$d" <<'PY' || fail "defects in the remeshed torus"
import json, sys
m, d = json.load(open(sys.argv[1])), float(sys.argv[2])
bad = {k: m[k] for k in ("non_manifold_edges", "non_manifold_vertices", "inconsistent_edges",
                         "boundary_edges", "boundary_loops", "duplicate_faces") if m[k] != 0}
if bad or m["genus"] != 1 or m["components"] != 1:
    print("FAIL:", bad, "genus", m["genus"], "components", m["components"]); sys.exit(1)
# Float storage rounds the coordinates (about 1e-7 of them here): every edge is d within 1e-5.
if m["edge_min"] < d * (1 - 1e-5):
    print("FAIL: shortest edge %g below d = %g" % (m["edge_min"], d)); sys.exit(1)
print("ok: %d vertices, %d faces, closed manifold torus, shortest edge %.6g >= d = %.6g"
      % (m["vertices"], m["faces"], m["edge_min"], d))
PY

# A point cloud: refused, with the reason, and no layer saved.
sphere_cloud "$work/cloud.ply"
cp "$GROWTH_SOURCE_DIR/scripts/mlx/spherepack_remesh.mlx" "$work/"
if mlserver -i cloud.ply -o cloud_remeshed.ply -s spherepack_remesh.mlx > "$work/cloud.log" 2>&1; then
  [ ! -f "$work/cloud_remeshed.ply" ] || [ "$(faces_of "$work/cloud_remeshed.ply")" -eq 0 ] \
    || fail "the remesher made faces from a point cloud"
fi
grep -q "The layer has no faces" "$work/cloud.log" || { cat "$work/cloud.log"; fail "no clear message for a point cloud"; }
echo "ok: a point cloud is refused"
