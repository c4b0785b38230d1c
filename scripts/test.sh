#!/usr/bin/env bash
# The README's test command (.ci/run calls it): sets up a fresh machine (scripts/setup.sh --all),
# builds everything, runs every test (unit, and integration through meshlabserver 2020.09 and the
# MeshLab 2025.07 hosts), then the Python package from its sdist in the real PyMeshLab wheel
# (scripts/test_python.sh), the unit tests under AddressSanitizer and UndefinedBehaviorSanitizer
# (scripts/sanitize.sh) and each fuzz target on a fixed sequence of inputs (scripts/fuzz.sh).
# GROWTH_FUZZ_SECONDS sets the fuzzing time per target (0: no fuzzing).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/setup.sh --all
# Also the PyMeshLab 2025.7 plugins (double, linked against the wheel in third_party/venv) and the
# MeshLab 2025.07 GUI plugins (float).
pymeshlab_dir=$(third_party/venv/bin/python -c 'import importlib.util, os; print(os.path.dirname(importlib.util.find_spec("pymeshlab").origin))')
cmake -S . -B build -DGROWTH_MESHLAB_2025D=ON -DGROWTH_MESHLAB_2025F=ON -DGROWTH_PYMESHLAB_DIR="$pymeshlab_dir"
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
# The Python package from its sdist (pip install), tested in the real wheel, against meshlabserver.
GROWTH_REQUIRE_MESHLAB2020=1 scripts/test_python.sh --sdist
scripts/sanitize.sh
fuzz_seconds=${GROWTH_FUZZ_SECONDS:-60}
# A fixed seed and number of inputs per target (see scripts/fuzz.sh), capped at 5 times the time.
if [ "$fuzz_seconds" -gt 0 ]; then GROWTH_FUZZ_SEED=${GROWTH_FUZZ_SEED:-1} scripts/fuzz.sh $((5 * fuzz_seconds)); fi
