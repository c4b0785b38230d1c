#!/usr/bin/env bash
# The sphere packer inside MeshLab: a generated cloud meshed by meshlabserver through the example
# script scripts/mlx/spherepack.mlx (automatic d and s); the result is a closed, manifold,
# consistently oriented mesh with per-face quality, every edge at least the d the filter logs.
source "$(dirname "$0")/meshlab_prefix.sh"
source "$(dirname "$0")/mesher_checks.sh"

sphere_cloud "$work/cloud.ply"
mlserver_mlx spherepack cloud.ply mesh.ply -m vn fq
grep -q "Sphere Packing: time [0-9.]* s" "$work/server.log" || fail "no time in the filter's log"
d=$(sed -n 's/.*Sphere Packing: .* d = \([0-9.eE+-]*\),.*/\1/p' "$work/server.log" | head -1)
[ -n "$d" ] || fail "no d in the filter's log"
LC_ALL=C sed -n '/^end_header/q;p' "$work/mesh.ply" | grep -q "property float quality" \
  || fail "the saved mesh has no per-face quality"
check_closed_sphere "$work/mesh.ply" "$d" quality
