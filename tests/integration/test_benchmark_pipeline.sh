#!/usr/bin/env bash
# The benchmark pipeline runs end to end on a small cloud: Ball Pivoting's row with its measures,
# a row for each of our filters (measured, or saying why not), the histograms plot. No timing is
# asserted (timings belong to the benchmark itself).
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_SOURCE_DIR/scripts/benchmark.sh" --no-build --build "$GROWTH_BUILD_DIR" --out "$work/out" \
  --clouds sphere-3k --methods bpa,spherepack,g2s > "$work/bench.log" 2>&1 \
  || { cat "$work/bench.log"; fail "benchmark failed"; }
md="$work/out/results.md"
[ -s "$md" ] || fail "no results.md"
grep -q '^## sphere-3k — 3,000 points' "$md" || fail "no table for sphere-3k"
bpa=$(grep '^| Ball Pivoting (auto radius) |' "$md") || fail "no Ball Pivoting row"
# A measured row (not a status line): its faces column holds a count.
faces=$(echo "$bpa" | awk -F'|' '{gsub(/[ ,]/, "", $6); print $6}')
[[ "$faces" =~ ^[0-9]+$ ]] && [ "$faces" -gt 1000 ] || fail "Ball Pivoting row without a mesh: $bpa"
for label in "Sphere Packing (ours)" "Robust G2S (ours)"; do
  grep -q "^| $label" "$md" || fail "no row for $label"
done
[ -s "$work/out/plots/sphere-3k_histograms.png" ] || fail "no histogram plot"
[ "$(wc -l < "$work/out/results.jsonl")" -eq 3 ] || fail "results.jsonl should hold 3 rows"
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
