#!/usr/bin/env bash
# Sets up a fresh machine, builds everything and runs every test (unit + meshlabserver integration).
# This is the README's test command; .ci/run calls it.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/setup.sh
cmake -S . -B build -DGROWTH_MESHLAB_2025D=ON   # also the MeshLab 2025.07d / PyMeshLab 2025.7 plugins
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
