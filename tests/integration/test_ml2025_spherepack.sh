#!/usr/bin/env bash
# The sphere packer in MeshLab 2025.07d (and, as integration.test_ml2025_spherepack.float, in the
# single-precision 2025.07), loaded and applied the way pymeshlab.load_plugin does
# (build/meshlab-2025.07d/ml_apply): on a closed cloud the mesh is closed, manifold, consistently
# oriented, every edge and vertex pair at least d; an absolute d given as a RichPercentage
# parameter is used as such; the counts equal those of the 2020.09 plugin through meshlabserver.
# ctest: once per MeshLab 2025.07 precision
source "$(dirname "$0")/meshlab_prefix.sh"
source "$(dirname "$0")/ml2025_env.sh"
source "$(dirname "$0")/mesher_checks.sh"
plugin="$plugins2025/libfilter_spherepack.so"

sphere_cloud "$work/cloud.ply"

# Automatic d (every parameter at its default).
ml_apply "$plugin" "Surface Reconstruction: Sphere Packing" "$work/cloud.ply" "$work/auto.ply" \
  > "$work/auto.log" 2>"$work/auto.err" || { cat "$work/auto.log" "$work/auto.err"; fail "ml_apply failed"; }
grep -qF "plugin: FilterSpherePack, built for MeshLab $ml_version, $ml_precision precision" "$work/auto.log" \
  || { cat "$work/auto.log"; fail "the plugin does not report MeshLab $ml_version, $ml_precision"; }
grep -q "^log: Sphere Packing: time [0-9.]* s" "$work/auto.log" || { cat "$work/auto.log"; fail "no filter log"; }
# Help texts short enough for MeshLab 2020.09's dialog to show them whole (the same glue source).
awk '/^help / { t = $0; sub(/^help [^:]*: [^:]*: /, "", t); if (length(t) > 100) { print; bad = 1 } }
     END { exit bad }' "$work/auto.log" || fail "help texts longer than 100 characters"
[ "$(grep -c '^help ' "$work/auto.log")" -eq 11 ] || fail "not 11 parameters with help texts"
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
startPoint2: startpoint2: numpy.ndarray[numpy.float64[3]]
keepFeatures: keepfeatures: bool
creaseAngle: creaseangle: float"
[ "$(sed -n 's/^python //p' "$work/auto.log")" = "$python_names" ] \
  || { grep '^python ' "$work/auto.log"; fail "the Python parameter names differ from the README's"; }
d=$(sed -n 's/^log: Sphere Packing: sphere diameter d = \([0-9.eE+-]*\),.*/\1/p' "$work/auto.log")
[ -n "$d" ] || fail "no d in the filter's log"
check_closed_sphere "$work/auto.ply" "$d" quality
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
check_closed_sphere "$work/given.ply" 0.08

# The 2020.09 plugin (float) through meshlabserver on the same cloud: the same counts.
mlserver_mlx spherepack cloud.ply mesh2020.ply
same_counts vertices "$(vertices_of "$work/auto.ply")" "$(vertices_of "$work/mesh2020.ply")"
same_counts faces "$(faces_of "$work/auto.ply")" "$(faces_of "$work/mesh2020.ply")"
