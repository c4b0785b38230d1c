#!/usr/bin/env bash
# The reference pipeline of the comparisons: a generated cloud, MeshLab's own Ball Pivoting run
# from an .mlx through meshlabserver, a mesh saved.
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 3000 --seed 2 -o "$work/cloud.ply" >/dev/null
cp "$GROWTH_SOURCE_DIR/scripts/mlx/ball_pivoting.mlx" "$work/bpa.mlx"
mlserver -i cloud.ply -o bpa.ply -m fq -s bpa.mlx > "$work/server.log" 2>&1 \
  || { cat "$work/server.log"; fail "meshlabserver failed"; }
[ -f "$work/bpa.ply" ] || { cat "$work/server.log"; fail "no mesh saved"; }
faces=$(faces_of "$work/bpa.ply")
# A closed sphere of 3000 points has about 6000 triangles; Ball Pivoting leaves some holes.
[ "${faces:-0}" -gt 4000 ] || fail "Ball Pivoting made only ${faces:-0} faces"
echo "ok: Ball Pivoting made $faces faces"
