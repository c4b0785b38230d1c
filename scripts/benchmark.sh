#!/usr/bin/env bash
# The comparison benchmark against MeshLab's Ball Pivoting. Builds the project, makes a
# scratch MeshLab prefix with the freshly built plugins (scripts/meshlab_env.sh), then runs
# scripts/benchmark.py (code in scripts/bench/), which writes out/benchmark/results.md (tables),
# results.jsonl and plots/.
#
#   scripts/benchmark.sh                 every generated cloud (sphere, torus, patch at 10k..1M
#                                        points) and every cloud of ../shared/data, with its own
#                                        normals and with MeshLab's (bunny-ml, ...): long (hours)
#   scripts/benchmark.sh --quick         10k and 30k points, hand and hand-ml: minutes
#   scripts/benchmark.sh --methods spherepack,bpa --clouds torus-60k      one method/cloud
#   scripts/benchmark.sh --methods g2s,cgal-afsr --clouds noisy,scans     Robust G2S against CGAL's
#                                        advancing front (build/afsr_run, built when CGAL is found) on
#                                        the noisy clouds (Gaussian noise 10/25/50 % of the spacing,
#                                        5/10/20 % outliers; noisy-50k: at 50k points) and the scans
#   scripts/benchmark.sh --report-only   rebuild the tables and plots from results.jsonl
#   scripts/benchmark.sh --report-only --remeasure   measure the saved meshes again (new measures or
#                                        histogram ranges), keeping the timings
#   scripts/benchmark.sh --retime [--clouds ..] [--methods ..]   time the saved rows of clouds up to
#                                        100k points again, in process (build/plugin_time)
#   scripts/benchmark.sh --floors [--clouds ..]   measure the no-op filter's memory (MeshLab's floor
#                                        for applying any filter) of the saved rows' clouds again
#   scripts/benchmark.sh --pymeshlab [--clouds torus-30k,hand] [--repeat 3]   the PyMeshLab row set
#                                        (scripts/benchmark_pymeshlab.py): both filters and Ball
#                                        Pivoting in one MeshSet of the venv's PyMeshLab 2025.7
#                                        (scripts/setup.sh --pymeshlab, package installed by
#                                        scripts/test_python.sh), written to out/benchmark/pymeshlab.md
#   scripts/benchmark.sh --scale [--points 10m] [--hosts meshlabserver,pymeshlab]   ten million points
#                                        for real: a scan-like cloud of make_cloud (6 parts,
#                                        noise, 2 % stray points, 1 % flipped normals) through
#                                        meshlabserver and PyMeshLab (the build's plugins, nothing
#                                        installed), one after the other, with the automatic parameters:
#                                        time, peak RSS, the mesh measures and the guarantees, written to
#                                        out/bench/scale-10m.md (scripts/benchmark_scale.py; uses the
#                                        build as it is; about 10 GB and minutes per host at 10M)
#   scripts/benchmark.sh --remesh [--meshes small|organic|medium|large|all|NAME,..] [--methods ier,cgal,ours]
#                                        [--plugin LIB.so] [--target-scale F] [--report-only]   the remeshing benchmark
#                                        (scripts/bench/remesh.py): MeshLab's Isotropic Explicit Remeshing
#                                        (PyMeshLab 2025.7, 3 iterations), CGAL's isotropic_remeshing
#                                        (build/isotropic_remesh_run, 3 iterations) and our Sphere Packing
#                                        remeshing (when the plugin has it) at the input's mean edge length,
#                                        measured against the input: out/benchmark/remesh.md and remesh.jsonl.
#                                        Uses the build as it is (make_mesh, mesh_measures, g2s_run,
#                                        make_cloud, isotropic_remesh_run); small: six generated 20k-face
#                                        meshes, seconds; large: 1M+ faces, many minutes
#   scripts/benchmark.sh --help          all options
#
# Options of this wrapper: --build DIR (default $GROWTH_BUILD_DIR or build/), --out DIR (default
# out/benchmark), --data-dir DIR (the folder of the public scans; default $GROWTH_DATA_DIR, else ../shared/data), --no-build (use the build as it is). Rows are merged into results.jsonl by
# (cloud, method) across invocations (--fresh starts over); each row records its run's date.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${GROWTH_BUILD_DIR:-$root/build}
out=$root/out/benchmark
data=${GROWTH_DATA_DIR:-$(cd "$root/.." && pwd)/shared/data}
command="scripts/benchmark.sh $*"

if [ "${1:-}" = "--pymeshlab" ]; then
  shift
  venv_python=$root/third_party/venv/bin/python
  [ -x "$venv_python" ] || { echo "benchmark: no venv: run scripts/setup.sh --pymeshlab" >&2; exit 1; }
  "$venv_python" -c 'import growth_meshers' 2>/dev/null ||
    { echo "benchmark: growth_meshers is not installed in the venv: run scripts/test_python.sh" >&2; exit 1; }
  [ -x "$build/make_cloud" ] || cmake --build "$build" --target make_cloud >/dev/null
  exec "$venv_python" "$root/scripts/benchmark_pymeshlab.py" --build "$build" --data-dir "$data" --out "$out" "$@"
fi

if [ "${1:-}" = "--remesh" ]; then
  shift
  rargs=()
  while [ $# -gt 0 ]; do
    case $1 in
      --build) build=$2; shift 2 ;;
      --out) out=$2; shift 2 ;;
      --data-dir) data=$2; shift 2 ;;
      --no-build) shift ;;   # the remeshing benchmark always uses the build as it is
      *) rargs+=("$1"); shift ;;
    esac
  done
  for tool in make_mesh mesh_measures; do
    [ -x "$build/$tool" ] || { echo "benchmark: no $build/$tool: build first (cmake --build $build --target $tool)" >&2; exit 1; }
  done
  # The PyMeshLab rows (IER, ours) need the venv; without it they are skipped with that reason.
  venv_python=$root/third_party/venv/bin/python
  py=()
  if [ -x "$venv_python" ] && "$venv_python" -c 'import pymeshlab' 2>/dev/null; then py=(--python "$venv_python"); fi
  exec /usr/bin/python3 "$root/scripts/bench/remesh.py" --build "$build" --out "$out" --data-dir "$data" \
    --command "$command" ${py[@]+"${py[@]}"} ${rargs[@]+"${rargs[@]}"}
fi

if [ "${1:-}" = "--scale" ]; then
  shift
  for tool in make_cloud mesh_measures plugins/libfilter_spherepack.so; do
    [ -e "$build/$tool" ] || { echo "benchmark: no $build/$tool: build first (cmake --build $build)" >&2; exit 1; }
  done
  for tool in /usr/bin/time xvfb-run; do
    command -v "$tool" >/dev/null || { echo "benchmark: $tool is missing: run scripts/setup.sh" >&2; exit 1; }
  done
  source "$root/scripts/meshlab_env.sh"
  make_meshlab_prefix "$build" "$root/out/bench/meshlab-prefix"
  exec /usr/bin/python3 "$root/scripts/benchmark_scale.py" --build "$build" --prefix "$root/out/bench/meshlab-prefix" \
    --out "$root/out/bench" --command "$command" "$@"
fi

args=()
skip_build=false
skip_prefix=false
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --data-dir) data=$2; shift 2 ;;
    --no-build) skip_build=true; shift ;;
    --report-only|-h|--help) skip_build=true; skip_prefix=true; args+=("$1"); shift ;;
    *) args+=("$1"); shift ;;
  esac
done
build=$(mkdir -p "$build" && cd "$build" && pwd)
mkdir -p "$out"
out=$(cd "$out" && pwd)

if ! /usr/bin/python3 -c 'import numpy, matplotlib' 2>/dev/null; then
  echo "benchmark: /usr/bin/python3 lacks numpy or matplotlib: run scripts/setup.sh" >&2
  exit 1
fi
for tool in /usr/bin/time xvfb-run; do
  command -v "$tool" >/dev/null || { echo "benchmark: $tool is missing: run scripts/setup.sh" >&2; exit 1; }
done

prefix=$out/meshlab-prefix
if ! $skip_build; then
  [ -f "$build/CMakeCache.txt" ] || cmake -S "$root" -B "$build"
  cmake --build "$build" -j2
fi
if ! $skip_prefix; then
  source "$root/scripts/meshlab_env.sh"
  make_meshlab_prefix "$build" "$prefix"
fi

exec /usr/bin/python3 "$root/scripts/benchmark.py" --out "$out" --build "$build" --prefix "$prefix" \
  --data-dir "$data" --command "$command" ${args[@]+"${args[@]}"}
