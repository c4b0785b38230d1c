#!/usr/bin/env bash
# The remeshing benchmark's pipeline on two tiny generated meshes (a box with a through hole, an open
# sheet with three holes): scripts/benchmark.sh --remesh runs MeshLab's IER (PyMeshLab), CGAL's
# isotropic remeshing (build/isotropic_remesh_run) and our row (measured, or skipped with its reason
# while the plugin has no remeshing filter), measures each output against its input and writes the
# report. Skips itself (77) without build/isotropic_remesh_run (no CGAL) or without the PyMeshLab
# venv. No timing is asserted. The targets' verdicts are checked on made-up rows.
set -euo pipefail
: "${GROWTH_BUILD_DIR:?set by ctest}"
: "${GROWTH_SOURCE_DIR:?set by ctest}"
fail() { echo "FAIL: $*" >&2; exit 1; }
work="$GROWTH_BUILD_DIR/integration/$(basename "$0" .sh)"
rm -rf "$work" && mkdir -p "$work"

cgal="$GROWTH_BUILD_DIR/isotropic_remesh_run"
venv_python="$GROWTH_SOURCE_DIR/third_party/venv/bin/python"
[ -x "$cgal" ] || { echo "SKIP: $cgal not built (no CGAL: libcgal-dev)"; exit 77; }
"$venv_python" -c 'import pymeshlab' 2>/dev/null || { echo "SKIP: no PyMeshLab venv (scripts/setup.sh --pymeshlab)"; exit 77; }

# The CGAL runner refuses what it cannot remesh, saying why.
"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 500 -o "$work/cloud.ply" >/dev/null
if "$cgal" "$work/cloud.ply" --target 0.1 -o "$work/x.ply" 2> "$work/err.txt"; then fail "a point cloud was remeshed"; fi
grep -q "cannot read a mesh with faces" "$work/err.txt" || fail "no clear error for a point cloud: $(cat "$work/err.txt")"
"$GROWTH_BUILD_DIR/make_mesh" --shape box --faces 500 -o "$work/box.ply" >/dev/null
if "$cgal" "$work/box.ply" --target -1 2> "$work/err.txt"; then fail "a negative target was accepted"; fi
grep -q "positive length" "$work/err.txt" || fail "no clear error for a negative target: $(cat "$work/err.txt")"

"$GROWTH_SOURCE_DIR/scripts/benchmark.sh" --remesh --build "$GROWTH_BUILD_DIR" --out "$work/out" \
  --meshes holedbox-2k,sheet-2k --fresh > "$work/bench.log" 2>&1 || { cat "$work/bench.log"; fail "benchmark failed"; }
md="$work/out/remesh.md"
[ -s "$md" ] || fail "no remesh.md"
for text in '^Commands (.*): `scripts/benchmark.sh --remesh' '^Date: .*Machine: .*CGAL 5\.5.*PyMeshLab 2025\.7' \
            '^## holedbox-2k — [0-9,]* faces, CAD, creases' '^## sheet-2k — [0-9,]* faces, open, holes' \
            '^| MeshLab IER (3 iterations) | [0-9.]* |' '^| CGAL isotropic_remeshing (3 iterations) | [0-9.]* |' \
            '^| Sphere Packing remeshing (ours) |' '^Targets for ours: '; do
  grep -q "$text" "$md" || fail "remesh.md has no line matching $text"
done
python3 - "$work/out/remesh.jsonl" <<'PY' || fail "wrong rows"
import json, math, sys
rows = {(r["mesh"], r["method"]): r for r in map(json.loads, open(sys.argv[1]))}
assert len(rows) == 6, sorted(rows)
expect = {"holedbox-2k": (1, 0), "sheet-2k": (0, 4)}   # genus, boundary loops
for mesh, (genus, loops) in expect.items():
    for method in ("ier", "cgal"):
        r = rows[(mesh, method)]
        assert r["status"] == "ok", (mesh, method, r["status"])
        m, m_in = r["measures"], r["input_measures"]
        d = r["target"]
        assert abs(d / m_in["edge_mean"] - 1) < 1e-9, (mesh, d)            # L = the input's mean edge
        assert m["faces"] > 500 and m["manifold"] and m["components"] == 1, (mesh, method, m["faces"])
        assert (m["genus"], m["boundary_loops"]) == (genus, loops), (mesh, method, m["genus"], m["boundary_loops"])
        assert m["quality_mean"] > m_in["quality_mean"] + 0.1, (mesh, method, m["quality_mean"], m_in["quality_mean"])
        for k in ("to_reference_mean", "to_reference_max", "from_reference_mean", "from_reference_max", "hausdorff"):
            assert m[k] is not None and math.isfinite(m[k]) and m[k] >= 0, (mesh, method, k, m[k])
        assert m["hausdorff"] < 1.5 * d, (mesh, method, m["hausdorff"] / d)
        assert m["from_reference_max"] >= m["from_reference_vertex_max"]
        assert abs(m["shortest_edge_over_d"] * d - m["edge_min"]) < 1e-9 * d
        assert r["seconds"] > 0 and r["peak_rss_mib"] >= r["load_rss_mib"] > 0, (mesh, method, r)
    ours = rows[(mesh, "ours")]
    assert ours["status"] == "ok" or ours["status"].startswith("skipped: ") and "meshing_sphere_packing_remeshing" in ours["status"], ours["status"]
# The box keeps its creases under both (IER's featuredeg and CGAL's constrained sharp edges): the
# output lies on the input, up to float rounding.
for method in ("ier", "cgal"):
    m = rows[("holedbox-2k", method)]["measures"]
    assert m["hausdorff"] < 1e-5 * rows[("holedbox-2k", method)]["target"], (method, m["hausdorff"])
PY

# The plumbing of our row (plugin, filter, parameters, saved layer, measures, verdicts), with one of
# PyMeshLab's own filters standing in for ours: it runs, is measured and gets the three verdicts.
"$GROWTH_SOURCE_DIR/scripts/benchmark.sh" --remesh --build "$GROWTH_BUILD_DIR" --out "$work/stand-in" --meshes box-1k \
  --methods ier,ours --our-filter meshing_remove_duplicate_vertices --fresh > "$work/stand-in.log" 2>&1 \
  || { cat "$work/stand-in.log"; fail "benchmark with a stand-in filter failed"; }
grep -q '^| box-1k | [a-zA-Z/]* (.*) | NO (shortest 0\.[0-9]* d, [0-9]* edges shorter than d) | n/a (.* input faces < 100k) |$' \
  "$work/stand-in/remesh.md" || { cat "$work/stand-in/remesh.md"; fail "no verdicts for the stand-in row"; }
grep -q '^Targets for ours: mean Q_t >= IER' "$work/stand-in/remesh.md" || fail "no targets line for the stand-in row"

# The targets' verdicts on made-up rows: ours better than IER everywhere, then worse on each.
PYTHONPATH="$GROWTH_SOURCE_DIR/scripts/bench" python3 - <<'PY' || fail "wrong verdicts"
import copy
import remesh
ier = {"method": "ier", "status": "ok", "seconds": 2.0, "input_faces": 200000, "measures": {"quality_mean": 0.93}}
ours = {"method": "ours", "status": "ok", "seconds": 1.0, "input_faces": 200000,
        "measures": {"quality_mean": 0.95, "edges_below_d": 0, "shortest_edge_over_d": 1.0}}
verdicts = lambda o, i=ier: [c[1] for c in remesh.checks([i, o])]
assert verdicts(ours) == ["yes", "yes", "yes"], verdicts(ours)
worse = copy.deepcopy(ours); worse["measures"]["quality_mean"] = 0.92
assert verdicts(worse)[0] == "NO"
short = copy.deepcopy(ours); short["measures"].update(edges_below_d=3, shortest_edge_over_d=0.8)
assert verdicts(short)[1] == "NO"
slow = copy.deepcopy(ours); slow["seconds"] = 3.0
assert verdicts(slow)[2] == "NO"
small = copy.deepcopy(slow); small["input_faces"] = 99999
assert verdicts(small)[2] == "n/a"
assert remesh.checks([ier, dict(ours, status="skipped: no filter")]) is None
assert remesh.mesh_names("small,box-20k,bunny-g2s") == remesh.GROUPS["small"] + ["bunny-g2s"]
PY
echo "ok: $(grep -c '^## ' "$md") tables in $md"
