# Sourced by scripts/sanitize.sh and scripts/fuzz.sh: configures build-asan/ (or $GROWTH_ASAN_BUILD),
# one build of clang with AddressSanitizer and UndefinedBehaviorSanitizer for both: the engine
# libraries, the unit tests and the libFuzzer targets (so CI compiles the engines once; the unit
# tests then carry the fuzzers' coverage counters too, which costs them little). -O2 with
# assertions on (no NDEBUG) but for Eigen's index checks (EIGEN_NO_DEBUG): at -O1 and with those
# checks, Eigen's small fixed-size loops took 4 times as long per fuzz input.
asan_build=${GROWTH_ASAN_BUILD:-build-asan}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

configure_sanitizer_build() {
  local cxx
  cxx=$(command -v clang++-14 || command -v clang++ || true)
  [ -n "$cxx" ] || { echo "clang++ not found: run scripts/setup.sh" >&2; return 1; }
  cmake -S . -B "$asan_build" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g -DEIGEN_NO_DEBUG" -DGROWTH_SANITIZERS=address,undefined \
        -DGROWTH_BUILD_FUZZERS=ON -DGROWTH_BUILD_PLUGINS=OFF >/dev/null
}
