#!/usr/bin/env bash
# A plugin of the wrong precision is refused, as PyMeshLab 2025.7 and the MeshLab 2025.07 GUIs
# refuse it: the double host (build/meshlab-2025.07d/ml_apply, like PyMeshLab and 2025.07d) given the
# float plugin, and the float host (build/meshlab-2025.07/ml_apply, like the plain 2025.07 GUI)
# given the double plugin, stop in PluginManager::checkPlugin with MeshLab's own message, exit with
# status 2 and write no mesh. Needs both builds (-DGROWTH_MESHLAB_2025D=ON -DGROWTH_MESHLAB_2025F=ON).
source "$(dirname "$0")/meshlab_prefix.sh"
for dir in "${GROWTH_2025D_DIR:-}" "${GROWTH_2025F_DIR:-}"; do
  if [ -z "$dir" ] || [ ! -x "$dir/ml_apply" ]; then
    echo "SKIP: needs both MeshLab 2025.07 builds (configure with -DGROWTH_MESHLAB_2025D=ON" \
         "-DGROWTH_MESHLAB_2025F=ON and build)"
    exit 77
  fi
done

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 2000 --seed 4 -o "$work/cloud.ply" >/dev/null
refused() { # host_dir plugin_dir plugin python_filter_name
  local host=$1 so=$2/plugins/libfilter_$3.so tag status=0
  tag="$(basename "$host")_$3"
  QT_QPA_PLATFORM=offscreen "$host/ml_apply" "$so" "$4" "$work/cloud.ply" "$work/out_$tag.ply" \
    > "$work/refused_$tag.log" 2>&1 || status=$?
  [ "$status" -eq 2 ] || { cat "$work/refused_$tag.log"; fail "$host/ml_apply on $so: exit status $status, not 2"; }
  grep -qxF "ml_apply: the plugin was refused: $(basename "$so") has different floating point precision from the running MeshLab version." \
    "$work/refused_$tag.log" || { cat "$work/refused_$tag.log"; fail "$host/ml_apply on $so: not MeshLab's precision message"; }
  [ ! -e "$work/out_$tag.ply" ] || fail "$host/ml_apply on $so wrote a mesh"
  echo "ok: $(basename "$host")/ml_apply refuses $so"
}
for filter in "spherepack generate_surface_reconstruction_sphere_packing" \
              "g2s generate_surface_reconstruction_robust_g2s"; do
  refused "$GROWTH_2025D_DIR" "$GROWTH_2025F_DIR" $filter
  refused "$GROWTH_2025F_DIR" "$GROWTH_2025D_DIR" $filter
done
