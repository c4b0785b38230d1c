#!/usr/bin/env bash
# Determinism through the plugins: two meshlabserver runs of each filter on the
# same noisy cloud write the same PLY, byte for byte. The second run is pinned to one CPU (taskset),
# so the sphere packer's threads (automatic: the hardware's) are scheduled quite differently.
# (tests/determinism_test.cpp compares the engines' meshes on 1 and 2 threads and on reruns.)
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_BUILD_DIR/make_cloud" --shape torus --points 24000 --seed 8 --noise 0.01 --outliers 0.02 \
  -o "$work/cloud.ply" > /dev/null
cp "$GROWTH_SOURCE_DIR/scripts/mlx/g2s.mlx" "$GROWTH_SOURCE_DIR/scripts/mlx/spherepack.mlx" "$work/"
pin=()
command -v taskset > /dev/null && pin=(taskset -c 0)

for filter in g2s spherepack; do
  mlserver -i cloud.ply -o "$filter-1.ply" -m vn fn fq -s "$filter.mlx" > "$work/$filter-1.log" 2>&1 \
    || { cat "$work/$filter-1.log"; fail "$filter: meshlabserver failed"; }
  ( cd "$work" && "${pin[@]}" xvfb-run -a "$prefix/bin/meshlabserver" -i cloud.ply -o "$filter-2.ply" \
      -m vn fn fq -s "$filter.mlx" ) > "$work/$filter-2.log" 2>&1 \
    || { cat "$work/$filter-2.log"; fail "$filter: meshlabserver failed (second run)"; }
  faces=$(faces_of "$work/$filter-1.ply")
  [ "$faces" -gt 10000 ] || fail "$filter: only $faces faces"
  cmp "$work/$filter-1.ply" "$work/$filter-2.ply" || fail "$filter: two runs wrote different meshes"
  echo "ok: $filter: two runs, the same $faces faces byte for byte ($(stat -c %s "$work/$filter-1.ply") bytes)"
done
