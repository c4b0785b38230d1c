#!/usr/bin/env bash
# Robust G2S in MeshLab 2025.07d (and, as integration.test_ml2025_g2s.float, in the single-precision
# 2025.07), loaded and applied the way pymeshlab.load_plugin does (build/meshlab-2025.07d/ml_apply,
# the filter named by its Python name): a closed torus cloud
# gives a closed, manifold, consistently oriented mesh on (nearly) every point, with the counts of
# the 2020.09 plugin through meshlabserver and the output dictionary; the loader refuses the
# 2020.09 plugin; a refused input fails with its message.
# ctest: once per MeshLab 2025.07 precision
source "$(dirname "$0")/meshlab_prefix.sh"
source "$(dirname "$0")/ml2025_env.sh"
source "$(dirname "$0")/mesher_checks.sh"
plugin="$plugins2025/libfilter_g2s.so"

torus_cloud "$work/torus.ply"
ml_apply "$plugin" generate_surface_reconstruction_robust_g2s "$work/torus.ply" "$work/mesh.ply" randomseed=1 \
  > "$work/apply.log" 2>"$work/apply.err" || { cat "$work/apply.log" "$work/apply.err"; fail "ml_apply failed"; }
grep -qF "plugin: FilterG2S, built for MeshLab $ml_version, $ml_precision precision" "$work/apply.log" \
  || { cat "$work/apply.log"; fail "the plugin does not report MeshLab $ml_version, $ml_precision"; }
# The keywords of PyMeshLab's apply_filter (listed in the README); randomseed=1 above used one.
python_names="seedSearchFactor: seedsearchfactor: float
maxSearchRadius: maxsearchradius: float
sizeLevels: sizelevels: int
flatnessLevels: flatnesslevels: int
removeNonManifoldVertices: removenonmanifoldvertices: bool
maxHoleEdges: maxholeedges: int
removeSmallHandles: removesmallhandles: bool
minComponentFaces: mincomponentfaces: int
randomSeed: randomseed: int"
[ "$(sed -n 's/^python //p' "$work/apply.log")" = "$python_names" ] \
  || { grep '^python ' "$work/apply.log"; fail "the Python parameter names differ from the README's"; }
grep -q "^log: Robust G2S: .* faces on" "$work/apply.log" || { cat "$work/apply.log"; fail "no filter log"; }
check_closed_torus "$work/mesh.ply"
verts=$(vertices_of "$work/mesh.ply")
faces=$(faces_of "$work/mesh.ply")
# The output dictionary PyMeshLab returns from apply_filter.
grep -qx "output vertices = $verts" "$work/apply.log" || { cat "$work/apply.log"; fail "output vertices is not $verts"; }
grep -qx "output faces = $faces" "$work/apply.log" || { cat "$work/apply.log"; fail "output faces is not $faces"; }
grep -qx "output holes = 0" "$work/apply.log" || { cat "$work/apply.log"; fail "output holes is not 0"; }
grep -q "^output seconds = " "$work/apply.log" || { cat "$work/apply.log"; fail "no output seconds"; }

# The 2020.09 plugin (float) through meshlabserver on the same cloud: the same counts.
mlserver_mlx g2s torus.ply mesh2020.ply
same_counts vertices "$verts" "$(vertices_of "$work/mesh2020.ply")"
same_counts faces "$faces" "$(faces_of "$work/mesh2020.ply")"

# The loader's checks run: MeshLab 2025.07 refuses the 2020.09 plugin.
if ml_apply "$GROWTH_BUILD_DIR/plugins/libfilter_g2s.so" "Surface Reconstruction: Robust G2S" \
     "$work/torus.ply" "$work/refused.ply" > "$work/refused.log" 2>&1; then
  fail "ml_apply accepted the 2020.09 plugin"
fi
grep -q "the plugin was refused" "$work/refused.log" || { cat "$work/refused.log"; fail "no refusal message"; }

# A refused input: applyFilter throws MLException (PyMeshLab raises it in Python); no mesh is saved.
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n2 0 0\n' \
  > "$work/line.ply"
if ml_apply "$plugin" generate_surface_reconstruction_robust_g2s "$work/line.ply" "$work/line_mesh.ply" \
     > "$work/line.log" 2>&1; then
  fail "ml_apply succeeded on three points on a line"
fi
grep -q "the filter failed: Robust G2S: All points of the layer lie on one straight line" "$work/line.log" \
  || { cat "$work/line.log"; fail "no clear error for points on a line"; }
[ ! -e "$work/line_mesh.ply" ] || fail "a mesh was saved although the filter failed"
