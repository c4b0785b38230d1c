#!/usr/bin/env bash
# The unit tests (ctest -L unit) built with AddressSanitizer (with LeakSanitizer) and
# UndefinedBehaviorSanitizer, in build-asan/: any memory error, leak or undefined behaviour aborts
# its test with a report. Needs scripts/setup.sh to have run (scripts/test.sh runs both).
# Usage: scripts/sanitize.sh [extra ctest arguments, e.g. -R FuzzRegressions]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source scripts/sanitizer_build.sh
jobs=${GROWTH_JOBS:-$(nproc)}
start=$SECONDS
configure_sanitizer_build
cmake --build "$asan_build" --target unit_tests -j"$jobs"
built=$SECONDS
ctest --test-dir "$asan_build" -L unit --output-on-failure -j"$jobs" "$@"
echo "sanitize.sh: build $((built - start)) s, tests $((SECONDS - built)) s"
