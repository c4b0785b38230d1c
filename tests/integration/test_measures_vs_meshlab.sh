#!/usr/bin/env bash
# mesh_measures agrees with MeshLab's own "Compute Topological Measures" on a Ball Pivoting mesh
# (which has holes, unreferenced vertices, several components and non-manifold vertices): edges,
# boundary edges, unreferenced vertices, components, non-manifold vertices, and the holes MeshLab
# counts once the non-manifold vertices are split (our boundary loops are defined that way).
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_BUILD_DIR/make_cloud" --shape torus --points 5000 --seed 3 -o "$work/cloud.ply" >/dev/null
cp "$GROWTH_SOURCE_DIR/scripts/mlx/ball_pivoting.mlx" "$work/bpa.mlx"
mlserver -i cloud.ply -o bpa.ply -s bpa.mlx > "$work/bpa.log" 2>&1 || { cat "$work/bpa.log"; fail "Ball Pivoting failed"; }

cat > "$work/topo.mlx" <<'MLX'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Compute Topological Measures"/>
 <filter name="Repair non Manifold Vertices by splitting">
  <Param name="VertDispRatio" type="RichFloat" value="0"/>
 </filter>
 <filter name="Compute Topological Measures"/>
</FilterScript>
MLX
mlserver -i bpa.ply -s topo.mlx > "$work/topo.log" 2>&1 || { cat "$work/topo.log"; fail "topological measures failed"; }

"$GROWTH_BUILD_DIR/mesh_measures" "$work/bpa.ply" --cloud "$work/cloud.ply" --histograms "$work/h" > "$work/measures.json" \
  || fail "mesh_measures failed"

# A number from our JSON, and the n-th match of a pattern in MeshLab's log.
ours() { sed -n "s/^ *\"$1\": \([0-9.eE+-]*\),*$/\1/p" "$work/measures.json"; }
theirs() { grep '^LOG' "$work/topo.log" | sed -n "s/$1/\1/p" | sed -n "${2:-1}p"; }

check() {
  local what=$1 a=$2 b=$3
  [ -n "$a" ] && [ -n "$b" ] || fail "$what: missing value (ours '$a', MeshLab '$b')"
  [ "$a" = "$b" ] || fail "$what: mesh_measures says $a, MeshLab says $b"
  echo "ok: $what = $a"
}
check faces "$(ours faces)" "$(theirs '.*F: *\([0-9]*\).*')"
check edges "$(ours edges)" "$(theirs '.*E: *\([0-9]*\) .*')"
check "unreferenced vertices" "$(ours unreferenced_vertices)" "$(theirs '.*Unreferenced Vertices \([0-9]*\).*')"
check "boundary edges" "$(ours boundary_edges)" "$(theirs '.*Boundary Edges \([0-9]*\).*')"
check components "$(ours components)" "$(theirs '.*composed by \([0-9]*\) connected.*')"
check "non-manifold vertices" "$(ours non_manifold_vertices)" "$(theirs '.*Mesh has \([0-9]*\) non two manifold vertices.*')"
check "holes (after splitting)" "$(ours boundary_loops)" "$(theirs '.*Mesh has \([0-9]*\) holes.*')"
[ "$(ours non_manifold_vertices)" -gt 0 ] || fail "the test mesh should have non-manifold vertices"

# The rest of the tool's contract: the cloud measures and the three histograms.
[ -n "$(ours mu_d_percent)" ] || fail "no mu_d_percent with --cloud"
for h in angles edges quality; do
  [ -s "$work/h_$h.csv" ] || fail "no histogram $h"
  head -1 "$work/h_$h.csv" | grep -q '^lo,hi,count$' || fail "histogram $h has no header"
done
[ "$(wc -l < "$work/h_angles.csv")" -eq 181 ] || fail "angle histogram should have 180 bins"
total=$(awk -F, 'NR>1 {s+=$3} END {print s}' "$work/h_quality.csv")
check "Q_t histogram total" "$total" "$(ours faces)"
