#!/usr/bin/env bash
# The smoke test of the ten-million-point benchmark (scripts/benchmark.sh --scale) on a
# scan-like cloud of 200,000 points (6 parts, noise, 2 % stray points, 1 % flipped normals):
# scripts/benchmark_scale.py runs it through meshlabserver 2020.09 and PyMeshLab 2025.7 (when the
# double-precision plugins are built and the venv exists; skipped otherwise) with the automatic
# parameters and checks the guarantees on both meshes (every edge and vertex pair >= d, manifold,
# no intersecting faces, every part meshed); both hosts show the progress of every phase and give
# the same mesh counts (within 1 %). Then what cancelling is in each host:
#   meshlabserver: its callback never returns false; Ctrl-C (SIGINT) ends it at once mid-filter,
#                  and no mesh is saved;
#   PyMeshLab:     its callback never returns false either, and Python holds a Ctrl-C until the
#                  filter returns; the plugins turn SIGINT into a cancel (growth/meshlab/interrupt.h):
#                  apply_filter stops within a second with the filter's "cancelled" error, no layer
#                  is added, and the interrupt then comes as KeyboardInterrupt.
source "$(dirname "$0")/meshlab_prefix.sh"
venv_python="$GROWTH_SOURCE_DIR/third_party/venv/bin/python"
with_pymeshlab=0
if [ -n "${GROWTH_2025D_DIR:-}" ] && [ -f "$GROWTH_2025D_DIR/plugins/libfilter_spherepack.so" ] && [ -x "$venv_python" ]; then
  with_pymeshlab=1
else
  echo "note: PyMeshLab part skipped (no -DGROWTH_MESHLAB_2025D=ON build or no third_party/venv)"
fi
hosts=meshlabserver$([ $with_pymeshlab -eq 1 ] && echo ,pymeshlab)

/usr/bin/python3 "$GROWTH_SOURCE_DIR/scripts/benchmark_scale.py" --points 200k --hosts "$hosts" --keep \
  --build "$GROWTH_BUILD_DIR" --prefix "$prefix" --out "$work" --python "$venv_python" \
  --command "ctest -R integration.test_scale_pipeline" > "$work/bench.out" 2>&1 \
  || { cat "$work/bench.out"; fail "the scale benchmark at 200k failed or a guarantee does not hold"; }
python3 - "$work/scale-200k.json" $with_pymeshlab <<'PY' || fail "the scale benchmark's results"
import json, sys
r = json.load(open(sys.argv[1]))
rows = {row["host"].split()[0]: row for row in r["rows"]}
want = ["meshlabserver"] + (["PyMeshLab"] if sys.argv[2] == "1" else [])
assert r["cloud"]["points"] == 200000, r["cloud"]["points"]
assert len(r["cloud"]["parts"]) == 6
phases = ["reading the cloud", "splat sizes", "box grid", "growing", "triangulating the regions", "writing the mesh"]
for host in want:
    row = rows[host]
    assert row["status"] == "ok", (host, row["status"])
    assert all(row["checks"].values()), (host, row["checks"])
    # One callback per percent (hosts drop repeats): about 85 in all, each phase seen.
    assert row["progress_callbacks"] >= 60, (host, row["progress_callbacks"])
    for p in phases:
        assert "Sphere packing: " + p in row["progress_phases"], (host, p, row["progress_phases"])
    print("%s: %d vertices, %d faces, %d holes, shortest edge %.7f d, %d components, %d progress callbacks, %.1f s, %.2f GB"
          % (host, row["measures"]["vertices"], row["measures"]["faces"], row["measures"]["boundary_loops"],
             row["measures"]["edge_min"] / row["d"], row["measures"]["components"], row["progress_callbacks"],
             row["wall_seconds"], row["peak_rss"] / 1e9))
if len(want) == 2:
    for k in ("vertices", "faces"):
        a, b = rows["meshlabserver"]["measures"][k], rows["PyMeshLab"]["measures"][k]
        assert abs(a - b) <= 0.01 * a, (k, a, b)
PY

# The cancels run on a cloud of a million points (a filter of several seconds: the signal always
# comes mid-filter), of the same kind.
cloud="$work/cancel-1m.ply"
"$GROWTH_BUILD_DIR/make_cloud" --shape scan --parts 6 --points 1000000 --seed 1 --gauss-spacings 0.1 \
  --outliers 0.02 --flip-normals 0.01 -o "$cloud" > /dev/null || fail "make_cloud"
# meshlabserver: Ctrl-C mid-filter (SIGINT from timeout, 4 s after the start: the cloud is loaded
# in about 1 s, the filter takes several) ends it at once; no mesh is saved.
cp "$GROWTH_SOURCE_DIR/scripts/mlx/spherepack.mlx" "$work/cancel.mlx"
start=$(date +%s.%N)
set +e
( cd "$work" && HOME="$work/scale-200k/meshlabserver/home" xvfb-run -a timeout -s INT 4 "$prefix/bin/meshlabserver" \
    -i "$cloud" -o cancelled.ply -s cancel.mlx > cancel.log 2>&1 )
rc=$?
set -e
elapsed=$(python3 -c "import sys, time; print('%.2f' % (time.time() - float(sys.argv[1])))" "$start")
[ "$rc" -eq 124 ] || { cat "$work/cancel.log"; fail "meshlabserver was not stopped by SIGINT (exit $rc after $elapsed s)"; }
[ ! -e "$work/cancelled.ply" ] || fail "meshlabserver saved a mesh after SIGINT"
grep -q "Surface Reconstruction: Sphere Packing" "$work/cancel.log" || { cat "$work/cancel.log"; fail "the filter had not started"; }
python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) < 4 + 1.0 else 1)" "$elapsed" \
  || fail "meshlabserver took until $elapsed s to stop after SIGINT at 4 s"
echo "meshlabserver: SIGINT 4 s after the start, in the filter: exited by $elapsed s, no mesh saved"

[ $with_pymeshlab -eq 1 ] || exit 0
# PyMeshLab: Ctrl-C (SIGINT) 2 s into apply_filter (past PyMeshLab's own set-up, in a run of several seconds) cancels the filter:
# it stops within a second, with the filter's "cancelled" error, adds no layer, and the interrupt
# comes afterwards as KeyboardInterrupt.
QT_QPA_PLATFORM=offscreen HOME="$work/scale-200k/pymeshlab/home" "$venv_python" - "$work/scale-200k/pymeshlab/pkg" "$cloud" <<'PY' \
  || fail "PyMeshLab's handling of Ctrl-C during apply_filter"
import signal, subprocess, sys, time
child = r'''
import signal, sys, time
signal.signal(signal.SIGINT, signal.default_int_handler)
sys.path.insert(0, sys.argv[1])
import pymeshlab, growth_meshers
ms = pymeshlab.MeshSet()
ms.load_new_mesh(sys.argv[2])
print("start", flush=True)
outcome, interrupted = None, False
try:
    try:
        ms.apply_filter("generate_surface_reconstruction_sphere_packing")
        outcome = "returned"
    except pymeshlab.PyMeshLabException as e:
        outcome = "cancelled" if "cancelled" in str(e) else "failed"
        time.sleep(2)  # the interrupt the plugin raises again arrives at once
except KeyboardInterrupt as k:
    interrupted = True
    if outcome is None:
        ctx = k.__context__
        outcome = "cancelled" if ctx is not None and "cancelled" in str(ctx) else "interrupted"
print("%s %d layers %d" % (outcome, interrupted, ms.mesh_number()), flush=True)
'''
p = subprocess.Popen([sys.executable, "-c", child, sys.argv[1], sys.argv[2]], stdout=subprocess.PIPE, universal_newlines=True)
assert p.stdout.readline().strip() == "start"
time.sleep(2.0)
t = time.time()
p.send_signal(signal.SIGINT)
line = p.stdout.readline().split()
after = time.time() - t
p.wait()
print("PyMeshLab: SIGINT 2 s into apply_filter:", " ".join(line), "(%.2f s after the signal)" % after)
assert line and line[0] == "cancelled", line  # the filter's own "cancelled" error ...
assert line[1] == "1", line                   # ... then KeyboardInterrupt
assert int(line[3]) == 1, line                # no layer added
assert after < 1.0, after                     # within a second
PY
