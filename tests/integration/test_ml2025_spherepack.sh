#!/usr/bin/env bash
# The sphere packer in MeshLab 2025.07d (and, as integration.test_ml2025_spherepack.float, in the
# single-precision 2025.07), loaded and applied the way pymeshlab.load_plugin does
# (build/meshlab-2025.07d/ml_apply): on a closed cloud the mesh is closed, manifold, consistently
# oriented, every edge and vertex pair at least d; an absolute d given as a RichPercentage
# parameter is used as such; the counts equal those of the 2020.09 plugin through meshlabserver.
# ctest: once per MeshLab 2025.07 precision
source "$(dirname "$0")/meshlab_prefix.sh"
source "$(dirname "$0")/ml2025_env.sh"
plugin="$plugins2025/libfilter_spherepack.so"

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 10000 --seed 2 -o "$work/cloud.ply" >/dev/null
check_mesh() { # mesh.ply d
  "$GROWTH_BUILD_DIR/mesh_measures" "$1" > "$1.json" || fail "mesh_measures failed on $1"
  python3 - "$1.json" "$2" <<'PY' || fail "defects in $1"
import json, sys
m, d = json.load(open(sys.argv[1])), float(sys.argv[2])
checks = [
    ("faces > 1000", m["faces"] > 1000),
    ("no boundary edges (closed)", m["boundary_edges"] == 0),
    ("no non-manifold edges", m["non_manifold_edges"] == 0),
    ("no non-manifold vertices", m["non_manifold_vertices"] == 0),
    ("consistently oriented", m["inconsistent_edges"] == 0),
    ("a sphere (Euler characteristic 2)", m["euler_characteristic"] == 2),
    ("every edge >= d (read back in float)", m["edge_min"] >= d * (1 - 1e-5)),
    ("every vertex pair >= d", m["min_vertex_distance"] >= d * (1 - 1e-5)),
]
bad = [name for name, ok in checks if not ok]
if bad:
    print("FAIL: " + "; ".join(bad) + "\n" + json.dumps(m, indent=1)); sys.exit(1)
print("ok: %d vertices, %d faces, smallest edge %.9g >= d = %.9g" % (m["vertices"], m["faces"], m["edge_min"], d))
PY
}

# Automatic d (every parameter at its default).
ml_apply "$plugin" "Surface Reconstruction: Sphere Packing" "$work/cloud.ply" "$work/auto.ply" \
  > "$work/auto.log" 2>"$work/auto.err" || { cat "$work/auto.log" "$work/auto.err"; fail "ml_apply failed"; }
grep -qF "plugin: FilterSpherePack, built for MeshLab $ml_version, $ml_precision precision" "$work/auto.log" \
  || { cat "$work/auto.log"; fail "the plugin does not report MeshLab $ml_version, $ml_precision"; }
grep -q "^log: Sphere Packing: time [0-9.]* s" "$work/auto.log" || { cat "$work/auto.log"; fail "no filter log"; }
# Help texts short enough for MeshLab 2020.09's dialog to show them whole (the same glue source).
awk '/^help / { t = $0; sub(/^help [^:]*: [^:]*: /, "", t); if (length(t) > 100) { print; bad = 1 } }
     END { exit bad }' "$work/auto.log" || fail "help texts longer than 100 characters"
[ "$(grep -c '^help ' "$work/auto.log")" -eq 9 ] || fail "not 9 parameters with help texts"
# The keywords of PyMeshLab's apply_filter, as MeshLab derives them (RichParameter::pythonName,
# pythonType), listed in the README.
python_names="sphereDiameter: spherediameter: PercentageValue
splatSize: splatsize: PercentageValue
localSplatSizes: localsplatsizes: bool
windowSize: windowsize: int
maxBorderLength: maxborderlength: int
minComponentFaces: mincomponentfaces: int
useStartPoints: usestartpoints: bool
startPoint1: startpoint1: numpy.ndarray[numpy.float64[3]]
startPoint2: startpoint2: numpy.ndarray[numpy.float64[3]]"
[ "$(sed -n 's/^python //p' "$work/auto.log")" = "$python_names" ] \
  || { grep '^python ' "$work/auto.log"; fail "the Python parameter names differ from the README's"; }
d=$(sed -n 's/^log: Sphere Packing: sphere diameter d = \([0-9.eE+-]*\),.*/\1/p' "$work/auto.log")
[ -n "$d" ] || fail "no d in the filter's log"
check_mesh "$work/auto.ply" "$d"
grep -qx "output vertices = $(vertices_of "$work/auto.ply")" "$work/auto.log" \
  || { cat "$work/auto.log"; fail "output vertices differs from the saved mesh"; }
grep -qx "output faces = $(faces_of "$work/auto.ply")" "$work/auto.log" \
  || { cat "$work/auto.log"; fail "output faces differs from the saved mesh"; }
grep -qx "output pieces_dropped = 0" "$work/auto.log" \
  || { cat "$work/auto.log"; fail "pieces were dropped on a clean cloud, or no pieces_dropped output"; }

# An absolute d through the RichPercentage parameter (parameters by their Python names).
ml_apply "$plugin" "Surface Reconstruction: Sphere Packing" "$work/cloud.ply" "$work/given.ply" \
  spherediameter=0.08 windowsize=8 > "$work/given.log" 2>"$work/given.err" \
  || { cat "$work/given.log" "$work/given.err"; fail "ml_apply failed with sphereDiameter=0.08"; }
grep -q "^log: Sphere Packing: sphere diameter d = 0.08," "$work/given.log" \
  || { cat "$work/given.log"; fail "sphereDiameter=0.08 was not used as an absolute length"; }
check_mesh "$work/given.ply" 0.08

# The 2020.09 plugin (float) through meshlabserver on the same cloud: the same counts.
cp "$GROWTH_SOURCE_DIR/scripts/mlx/spherepack.mlx" "$work/spherepack.mlx"
mlserver -i cloud.ply -o mesh2020.ply -s spherepack.mlx > "$work/server.log" 2>&1 \
  || { cat "$work/server.log"; fail "meshlabserver failed"; }
same_counts vertices "$(vertices_of "$work/auto.ply")" "$(vertices_of "$work/mesh2020.ply")"
same_counts faces "$(faces_of "$work/auto.ply")" "$(faces_of "$work/mesh2020.ply")"
