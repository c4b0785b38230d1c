#!/usr/bin/env bash
# Sets up, builds, generates the bundled sample (a seeded torus cloud with normals) and meshes it with
# both filters through meshlabserver and the example scripts in scripts/mlx/. Prints where the meshes are.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$(pwd)
start=$SECONDS
scripts/setup.sh
# Only what the demo runs: the two MeshLab 2020.09 plugins and the cloud generator.
cmake -S . -B build -DGROWTH_BUILD_TESTS=OFF >/dev/null
cmake --build build -j"$(nproc)" --target filter_spherepack filter_g2s make_cloud >/dev/null
echo "demo: set-up and build took $((SECONDS - start)) s"
source scripts/meshlab_env.sh

out="$root/out/demo"
mkdir -p "$out"
make_meshlab_prefix "$root/build" "$out/meshlab-prefix"
build/make_cloud --shape torus --points 30000 --seed 1 -o "$out/torus.ply"

for filter in spherepack g2s; do
  ( cd "$out" && run_meshlabserver "$out/meshlab-prefix" -i torus.ply -o "torus_$filter.ply" -m fq \
      -s "$root/scripts/mlx/$filter.mlx" > "$filter.log" 2>&1 ) || {
    cat "$out/$filter.log"; echo "demo: $filter failed (log above)" >&2; exit 1; }
  # meshlabserver prints the progress phases ("Robust G2S: growing the mesh") without a newline:
  # drop them, keep the filter's log lines.
  sed -E 's/(Sphere packing|Robust G2S): (reading|growing|removing|writing|box|splat|starting|triangulating) [a-z -]*(points|mesh|vertices|cloud|grid|sizes|regions)//g' "$out/$filter.log" |
    grep -E "^(Sphere Packing|Robust G2S)" | sed 's/^/  /' || true
  echo "demo: $filter mesh written to $out/torus_$filter.ply ($(ply_faces "$out/torus_$filter.ply") faces)"
done
echo "demo: done in $((SECONDS - start)) s"
