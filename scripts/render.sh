#!/usr/bin/env bash
# Makes the README's pictures: meshes the hand scan and the Stanford Bunny with both engines at their
# default parameters (build/spherepack_run and build/g2s_run: the engines the filters run, without
# MeshLab) and renders each mesh with scripts/render.py into docs/images/.
# Usage: scripts/render.sh [BUILD_DIR]     (default: build; needs spherepack_run and g2s_run there)
# The scans are read from GROWTH_DATA_DIR (default: ../shared/data); they are never copied into the
# repository. The meshes stay in out/render/ (ignored by git).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
data=${GROWTH_DATA_DIR:-../shared/data}
out=out/render
images=docs/images
for tool in spherepack_run g2s_run; do
  [ -x "$build/$tool" ] || { echo "render.sh: $build/$tool is missing (build the project first)" >&2; exit 1; }
done
mkdir -p "$out" "$images"

mesh() {  # mesh SCAN NAME: both engines, default parameters
  local scan="$data/$1.ply" name=$2
  [ -f "$scan" ] || { echo "render.sh: $scan is missing (see README, Data credits)" >&2; exit 1; }
  nice "$build/spherepack_run" "$scan" -o "$out/${name}_spherepack.ply" > "$out/${name}_spherepack.log" 2>&1
  nice "$build/g2s_run" "$scan" -o "$out/${name}_g2s.ply" > "$out/${name}_g2s.log" 2>&1
}
mesh hand hand
mesh bunny_merged_normals bunny

# The close-up windows (centre x, y and width, in fractions of the whole view): the knuckle of the
# hand's middle finger; the bunny's flank, where several of its range scans overlap.
render() {  # render NAME FILTER TITLE WINDOW
  nice /usr/bin/python3 scripts/render.py "$out/${1}_$2.ply" -o "$images/${1}_$2.png" --title "$3" --window "$4"
}
render hand spherepack "Sphere Packing on the hand scan (52,398 points), default parameters" 0.5,0.5,0.1
render hand g2s "Robust G2S on the hand scan (52,398 points), default parameters" 0.5,0.5,0.1
render bunny spherepack "Sphere Packing on the Stanford Bunny (361,489 points), default parameters" 0.55,0.5,0.1
render bunny g2s "Robust G2S on the Stanford Bunny (361,489 points), default parameters" 0.55,0.5,0.1
ls -l "$images"/*.png
