#!/usr/bin/env bash
# `cmake --install` of the MeshLab 2025.07d plugins (and, as integration.test_ml2025_install.float,
# of the single-precision 2025.07 ones) into a scratch prefix, component meshlab-VERSION: exactly
# the two plugins land in PREFIX/lib/meshlab-VERSION/plugins/; they, like the build-tree copies, name
# libmeshlab-common and Qt by soname only and carry no RUNPATH/RPATH (so a host binds them to its own
# libraries); the installed plugins load and mesh a cloud through ml_apply.
# ctest: once per MeshLab 2025.07 precision
source "$(dirname "$0")/meshlab_prefix.sh"
source "$(dirname "$0")/ml2025_env.sh"

prefix="$work/prefix"
cmake --install "$GROWTH_BUILD_DIR" --prefix "$prefix" --component "meshlab-$ml_version" > "$work/install.log" \
  || { cat "$work/install.log"; fail "cmake --install failed"; }
installed=$(cd "$prefix" && find . -type f -o -type l | sort | tr '\n' ' ')
expected="./lib/meshlab-$ml_version/plugins/libfilter_g2s.so ./lib/meshlab-$ml_version/plugins/libfilter_spherepack.so "
[ "$installed" = "$expected" ] || fail "installed: '$installed'; expected: '$expected'"

for so in "$prefix/lib/meshlab-$ml_version/plugins/"*.so "$plugins2025/"*.so; do
  dyn=$(readelf -d "$so")
  ! grep -qE '\((RUNPATH|RPATH)\)' <<< "$dyn" || { echo "$dyn"; fail "$so carries a RUNPATH or RPATH"; }
  grep -qF '(NEEDED)             Shared library: [libmeshlab-common.so]' <<< "$dyn" \
    || { echo "$dyn"; fail "$so does not name libmeshlab-common.so by soname"; }
  grep -q '(NEEDED).*\[libQt5Core.so.5\]' <<< "$dyn" || { echo "$dyn"; fail "$so does not name Qt5Core by soname"; }
  ! grep -q '(NEEDED).*\[.*/' <<< "$dyn" || { echo "$dyn"; fail "$so names a library by path"; }
done
echo "ok: $expected- soname-only NEEDED entries, no RUNPATH"

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 3000 --seed 5 -o "$work/cloud.ply" >/dev/null
ml_apply "$prefix/lib/meshlab-$ml_version/plugins/libfilter_spherepack.so" \
  generate_surface_reconstruction_sphere_packing "$work/cloud.ply" "$work/mesh.ply" > "$work/apply.log" 2>&1 \
  || { cat "$work/apply.log"; fail "ml_apply failed on the installed sphere-packing plugin"; }
grep -q "^output faces = [1-9]" "$work/apply.log" || { cat "$work/apply.log"; fail "no faces from the installed plugin"; }
ml_apply "$prefix/lib/meshlab-$ml_version/plugins/libfilter_g2s.so" \
  generate_surface_reconstruction_robust_g2s "$work/cloud.ply" "$work/mesh_g2s.ply" > "$work/apply_g2s.log" 2>&1 \
  || { cat "$work/apply_g2s.log"; fail "ml_apply failed on the installed Robust G2S plugin"; }
grep -q "^output faces = [1-9]" "$work/apply_g2s.log" || { cat "$work/apply_g2s.log"; fail "no faces from the installed G2S plugin"; }
echo "ok: the installed plugins mesh a cloud ($(faces_of "$work/mesh.ply") and $(faces_of "$work/mesh_g2s.ply") faces)"
