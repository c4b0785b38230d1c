# Sourced, after meshlab_prefix.sh, by the tests that run one of our filters on a closed generated
# cloud, through meshlabserver (MeshLab 2020.09) or ml_apply (MeshLab 2025.07): the clouds and the
# checks of the meshes they share. Provides torus_cloud, sphere_cloud, mlserver_mlx,
# check_closed_torus and check_closed_sphere.

# The closed clouds: a torus of 20,000 points (Robust G2S), a sphere of 10,000 (the sphere packer).
torus_points=20000
torus_cloud() { "$GROWTH_BUILD_DIR/make_cloud" --shape torus --points $torus_points --seed 3 -o "$1" >/dev/null; }
sphere_cloud() { "$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 10000 --seed 2 -o "$1" >/dev/null; }

# mlserver_mlx <script> <input> <output> [meshlabserver options]: scripts/mlx/<script>.mlx applied by
# meshlabserver in $work (input and output relative to it); its log in $work/server.log.
mlserver_mlx() {
  local script=$1 input=$2 output=$3
  shift 3
  cp "$GROWTH_SOURCE_DIR/scripts/mlx/$script.mlx" "$work/$script.mlx"
  mlserver -i "$input" -o "$output" "$@" -s "$script.mlx" > "$work/server.log" 2>&1 \
    || { cat "$work/server.log"; fail "meshlabserver failed with $script.mlx on $input"; }
  [ -f "$work/$output" ] || { cat "$work/server.log"; fail "meshlabserver saved no $output"; }
}

# check_closed_torus <mesh.ply>: the mesh of the torus cloud is a closed torus on (nearly) every
# point, F = 2V (Euler characteristic 0), manifold and consistently oriented, with no duplicate faces.
check_closed_torus() {
  local mesh=$1 verts faces
  verts=$(vertices_of "$mesh")
  faces=$(faces_of "$mesh")
  [ "$verts" -ge $((torus_points - torus_points / 400)) ] || fail "only $verts of $torus_points points used"
  [ "$faces" -eq $((2 * verts)) ] || fail "$faces faces on $verts vertices: not a closed torus"
  "$GROWTH_BUILD_DIR/mesh_measures" "$mesh" --no-min-vertex-distance > "$mesh.json" \
    || fail "mesh_measures failed on $mesh"
  python3 - "$mesh.json" <<'PY' || fail "defects in the torus mesh $mesh"
import json, sys
m = json.load(open(sys.argv[1]))
bad = {k: m[k] for k in ("non_manifold_edges", "non_manifold_vertices", "inconsistent_edges",
                         "boundary_edges", "boundary_loops", "duplicate_faces") if m[k] != 0}
if bad or m["euler_characteristic"] != 0:
    print("FAIL:", bad, "Euler characteristic", m["euler_characteristic"]); sys.exit(1)
print("ok: %d vertices, %d faces, closed manifold torus" % (m["vertices"], m["faces"]))
PY
}

# check_closed_sphere <mesh.ply> <d> [quality]: the sphere packer's mesh of the sphere cloud is a
# closed, manifold, consistently oriented sphere of more than 1500 faces, every edge and vertex pair
# at least d (read back in float); with "quality", also Q_avg >= 0.94 and E_RMS <= 16 % (the
# filter's automatic d).
check_closed_sphere() {
  "$GROWTH_BUILD_DIR/mesh_measures" "$1" > "$1.json" || fail "mesh_measures failed on $1"
  python3 - "$1.json" "$2" "${3:-}" <<'PY' || fail "defects in the sphere mesh $1"
import json, sys
m, d, quality = json.load(open(sys.argv[1])), float(sys.argv[2]), sys.argv[3] == "quality"
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
]
if quality:
    checks += [("Q_avg >= 0.94", m["quality_mean"] >= 0.94), ("E_RMS <= 16 %", m["edge_rms_percent"] <= 16)]
bad = [name for name, ok in checks if not ok]
if bad:
    print("FAIL: " + "; ".join(bad) + "\n" + json.dumps(m, indent=1))
    sys.exit(1)
print("ok: %d vertices, %d faces, Q_avg %.4f, E_RMS %.1f %%, smallest edge %.9g >= d = %.9g"
      % (m["vertices"], m["faces"], m["quality_mean"], m["edge_rms_percent"], m["edge_min"], d))
PY
}
