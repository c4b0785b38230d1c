# Sourced by scripts/sanitize.sh and scripts/fuzz.sh: configures build-asan/ (or $GROWTH_ASAN_BUILD),
# one build of clang with AddressSanitizer and UndefinedBehaviorSanitizer: the engine libraries
# and the unit tests. -O2 (Eigen at -O1 is several times slower
# under the fuzzers' comparison tracing) with assertions on (no NDEBUG), but for Eigen's index
# checks (EIGEN_NO_DEBUG: they doubled the time per input; AddressSanitizer checks the accesses).
asan_build=${GROWTH_ASAN_BUILD:-build-asan}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

configure_sanitizer_build() {
  local cxx
  cxx=$(command -v clang++-14 || command -v clang++ || true)
  [ -n "$cxx" ] || { echo "clang++ not found: run scripts/setup.sh" >&2; return 1; }
  cmake -S . -B "$asan_build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g -DEIGEN_NO_DEBUG" -DGROWTH_SANITIZERS=address,undefined \
        -DGROWTH_BUILD_PLUGINS=OFF >/dev/null
}
