#!/usr/bin/env bash
# The benchmark's peer, CGAL's advancing front (build/afsr_run, built only when CGAL is found): on a
# clean sphere it writes a mesh with faces, almost closed and manifold, and prints its time; the
# benchmark's "cgal-afsr" row on a noisy generated cloud (sphere-3k-gauss25) is measured. Skips
# itself (77) when afsr_run was not built.
source "$(dirname "$0")/meshlab_prefix.sh"

afsr="$GROWTH_BUILD_DIR/afsr_run"
[ -x "$afsr" ] || { echo "SKIP: $afsr not built (no CGAL: libcgal-dev)"; exit 77; }

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 5000 --seed 3 -o "$work/sphere.ply" >/dev/null
"$afsr" "$work/sphere.ply" -o "$work/mesh.ply" > "$work/afsr.txt" || fail "afsr_run failed: $(cat "$work/afsr.txt")"
key() { sed -n "s/^$1: //p" "$work/afsr.txt"; }
[ "$(key points)" = 5000 ] || fail "afsr_run read $(key points) points, not 5000"
[ "$(faces_of "$work/mesh.ply")" = "$(key faces)" ] || fail "the saved mesh has $(faces_of "$work/mesh.ply") faces, afsr_run said $(key faces)"
for k in seconds seconds_total; do
  [[ "$(key $k)" =~ ^[0-9]+\.[0-9]+$ ]] || fail "no $k: $(cat "$work/afsr.txt")"
done
"$GROWTH_BUILD_DIR/mesh_measures" "$work/mesh.ply" --no-min-vertex-distance > "$work/measures.json"
python3 - "$work/measures.json" <<'PY' || fail "afsr_run's mesh of a clean sphere is not an almost closed manifold mesh"
import json, sys
m = json.load(open(sys.argv[1]))
# A closed sphere of V vertices has 2V - 4 faces; the advancing front may leave a few small holes.
assert m["faces"] >= 1.95 * 5000, m["faces"]
assert m["vertices"] <= 5000 and m["vertices"] >= 0.99 * 5000, m["vertices"]
assert m["non_manifold_vertices"] == 0 and m["non_manifold_edges"] == 0, m
assert m["boundary_edges"] <= 0.01 * m["faces"], m["boundary_edges"]
PY

# The benchmark row, on a noisy cloud: Gaussian noise of 25 % of the clean cloud's spacing.
"$GROWTH_SOURCE_DIR/scripts/benchmark.sh" --no-build --build "$GROWTH_BUILD_DIR" --out "$work/out" \
  --clouds sphere-3k-gauss25 --methods cgal-afsr --repeat 1 > "$work/bench.log" 2>&1 \
  || { cat "$work/bench.log"; fail "benchmark failed"; }
python3 - "$work/out/results.jsonl" <<'PY' || fail "no measured cgal-afsr row"
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
assert len(rows) == 1, rows
r = rows[0]
assert (r["cloud"], r["method"], r["status"], r["perturbation"]) == ("sphere-3k-gauss25", "cgal-afsr", "ok", "gauss25"), r
assert r["time_source"] == "afsr_run" and r["time"] > 0, r
assert r["measures"]["faces"] > 3000 and r["measures"]["self_intersecting_pairs"] >= 0, r["measures"]
PY
grep -q '^| CGAL Advancing Front (defaults) | [0-9.]*‡ |' "$work/out/results.md" || fail "no cgal-afsr line in results.md"
echo "afsr_run: $(key faces) faces on 5000 points in $(key seconds) s"
