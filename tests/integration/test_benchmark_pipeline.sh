#!/usr/bin/env bash
# The benchmark pipeline runs end to end on a small cloud: Ball Pivoting's row with its measures,
# a row for each of our filters (measured, or saying why not), the histograms plot; then the same
# cloud with MeshLab's normals ("-ml") and the sphere packer at d = 2.5 x spacing, one run, merged
# into the same results. No timing is asserted (timings belong to the benchmark itself).
source "$(dirname "$0")/meshlab_prefix.sh"

bench() {
  "$GROWTH_SOURCE_DIR/scripts/benchmark.sh" --no-build --build "$GROWTH_BUILD_DIR" --out "$work/out" "$@" \
    >> "$work/bench.log" 2>&1 || { cat "$work/bench.log"; fail "benchmark $* failed"; }
}
bench --clouds sphere-3k --methods bpa,spherepack,spherepack25,g2s
bench --clouds sphere-3k-ml --methods spherepack25 --repeat 1
md="$work/out/results.md"
[ -s "$md" ] || fail "no results.md"
grep -q '^## sphere-3k — 3,000 points' "$md" || fail "no table for sphere-3k"
bpa=$(grep '^| Ball Pivoting (auto radius) |' "$md") || fail "no Ball Pivoting row"
# A measured row (not a status line): its faces column holds a count.
faces=$(echo "$bpa" | awk -F'|' '{gsub(/[ ,]/, "", $6); print $6}')
[[ "$faces" =~ ^[0-9]+$ ]] && [ "$faces" -gt 1000 ] || fail "Ball Pivoting row without a mesh: $bpa"
for label in "Sphere Packing (ours) d=" "Sphere Packing (ours, d = 2.5 × spacing) d=" "Robust G2S (ours)"; do
  grep -qF "| $label" "$md" || fail "no row for $label"
done
[ -s "$work/out/plots/sphere-3k_histograms.png" ] || fail "no histogram plot"
[ -s "$work/out/runs/sphere-3k/spherepack25/hist_edges.csv" ] || fail "no histograms for spherepack25"
[ "$(wc -l < "$work/out/results.jsonl")" -eq 5 ] || fail "results.jsonl should hold 5 rows"
# The new columns; the sphere packer's row shows its unreached points and started components.
for column in "self-intersecting pairs" "components" "unreached points (components started)"; do
  grep -q "^| method |.*| $column |" "$md" || fail "no column '$column'"
done
grep -F "| Sphere Packing (ours) d=" "$md" | grep -Eq '\| [0-9,]+ \([0-9,]+\) \|' \
  || fail "no unreached points in the sphere packer's row"
# The -ml cloud: the same points with MeshLab's normals, made by the benchmark; spherepack25 got
# d = 2.5 x the mean spacing.
grep -q '^## sphere-3k-ml — 3,000 points' "$md" || fail "no table for sphere-3k-ml"
[ "$(vertices_of "$work/out/clouds/sphere-3k-ml.ply")" = 3000 ] || fail "sphere-3k-ml.ply: not 3000 vertices"
python3 - "$work/out/results.jsonl" <<'PY' || fail "wrong -ml or spherepack25 rows"
import json, sys
rows = {(r["cloud"], r["method"]): r for r in map(json.loads, open(sys.argv[1]))}
ml = rows[("sphere-3k-ml", "spherepack25")]
assert ml["normals"] == "meshlab" and rows[("sphere-3k", "spherepack")]["normals"] == "own", "normals"
for key in [("sphere-3k", "spherepack25"), ("sphere-3k-ml", "spherepack25")]:
    r = rows[key]
    assert r["status"] == "ok", (key, r["status"])
    assert abs(r["info"]["d"] / (2.5 * r["spacing"]) - 1) < 1e-3, (key, r["info"]["d"], r["spacing"])
    assert r["info"]["unreached_points"] >= 0 and r["info"]["components_started"] >= 1, key
    assert r["measures"]["components"] >= 1, key
PY
# On a cloud this small every filter is timed in process (build/plugin_time), all by one clock, and
# each time is positive (so Ball Pivoting's speed-up against itself is defined: x1.00).
python3 - "$work/out/results.jsonl" <<'PY' || fail "rows not timed in process"
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
bad = [(r["method"], r.get("time_source"), r.get("time")) for r in rows
       if r.get("time_source") != "in process" or not r.get("time", 0) > 0]
if bad:
    sys.exit("not timed in process: %s" % bad)
PY
echo "$bpa" | grep -q '| ×1.00 |' || fail "Ball Pivoting's speed-up against itself is not x1.00: $bpa"
# Memory: every row carries the no-op filter floor of its cloud (MeshLab's cost of applying any
# filter), and the table shows the extra peak over load+save and over that floor.
python3 - "$work/out/results.jsonl" <<'PY' || fail "rows without the no-op filter floor"
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
bad = [r["method"] for r in rows if not (r.get("noop_rss_kb") or 0) > 0]
if bad:
    sys.exit("no noop_rss_kb: %s" % bad)
PY
echo "$bpa" | grep -Eq '\| [0-9]+ / [0-9]+ \|$' || fail "no 'over load+save / over no-op' memory column: $bpa"
echo "ok: $bpa"
