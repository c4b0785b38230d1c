#!/usr/bin/env bash
# Sets up a fresh machine, builds everything and runs every test (unit + meshlabserver integration),
# then the unit tests under AddressSanitizer and UndefinedBehaviorSanitizer (scripts/sanitize.sh)
# and each fuzz target for a minute (scripts/fuzz.sh). This is the README's test command; .ci/run
# calls it. GROWTH_FUZZ_SECONDS sets the fuzzing time per target (0: no fuzzing).
# The sanitizer part, measured on the 2-core development machine under load from other work
# (2026-12-02): a clean build of build-asan/ (unit tests and fuzzers) 11-12 min wall, 6 min CPU;
# the sanitized unit tests 10 min wall with ctest -j2, most of it one sphere-packer coverage test
# (2.6 min CPU); the fuzzers 2 min plus their link.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/setup.sh
# Also the MeshLab 2025.07d / PyMeshLab 2025.7 (double) and the MeshLab 2025.07 (float) plugins.
cmake -S . -B build -DGROWTH_MESHLAB_2025D=ON -DGROWTH_MESHLAB_2025F=ON
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
scripts/sanitize.sh
fuzz_seconds=${GROWTH_FUZZ_SECONDS:-60}
# A fixed seed and number of inputs per target (see scripts/fuzz.sh), capped at 5 times the time.
if [ "$fuzz_seconds" -gt 0 ]; then GROWTH_FUZZ_SEED=${GROWTH_FUZZ_SEED:-1} scripts/fuzz.sh $((5 * fuzz_seconds)); fi
