#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang with AddressSanitizer and UndefinedBehaviorSanitizer,
# in build-asan/) and runs each for SECONDS (default 60), one after the other:
#   fuzz_ply    arbitrary bytes as a PLY file -> vcglib's importer -> both engines
#   fuzz_cloud  arbitrary bytes as the recipe of a cloud and of both engines' parameters
# Each starts from its seed corpus in fuzz/corpus/<target>/ (read only) and from what earlier runs
# found, kept in build-asan/fuzz-corpus/<target>/ (new inputs go there). A finding stops the run
# with the input in build-asan/fuzz-artifacts/<target>/ and a non-zero exit; replay it with
#   build-asan/fuzz/fuzz_<target> <input>
# and, once fixed, keep it in fuzz/regressions/<target>/ (tests/fuzz_regressions_test.cpp).
# Needs scripts/setup.sh to have run (scripts/test.sh runs both).
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: ply cloud; default both)
# With GROWTH_FUZZ_SEED set (scripts/test.sh, i.e. CI, sets 1), each target runs a fixed number of
# inputs (ply 20,000, cloud 1,000: about a minute each) from that seed, SECONDS then only a cap:
# the same inputs on every run of the same code, so that CI does not pass or fail by chance.
# Without it (exploring by hand), a random seed for SECONDS.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source scripts/sanitizer_build.sh
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(ply cloud)

configure_sanitizer_build
cmake --build "$asan_build" --target fuzzers -j"${GROWTH_JOBS:-$(nproc)}"

# Per input: at most 25 s (every input the harness accepts takes well under a second), 2 GB.
# Longest input: a PLY file of a few thousand points; a cloud recipe reads fewer than 100 bytes.
declare -A max_len=([ply]=65536 [cloud]=256)
declare -A fixed_runs=([ply]=20000 [cloud]=1000)
status=0
for t in "${targets[@]}"; do
  [ -n "${max_len[$t]:-}" ] || { echo "fuzz.sh: unknown target $t (ply, cloud)" >&2; exit 2; }
  corpus="$asan_build/fuzz-corpus/$t" artifacts="$asan_build/fuzz-artifacts/$t" log="$asan_build/fuzz-$t.log"
  mkdir -p "$corpus" "$artifacts"
  echo "fuzz.sh: fuzz_$t for $seconds s (log: $log)"
  start=$SECONDS
  fixed=()
  if [ -n "${GROWTH_FUZZ_SEED:-}" ]; then
    # A fixed sequence: a fresh corpus each run (what earlier runs found would change it), the seed,
    # a number of inputs.
    corpus=$(mktemp -d)
    fixed=(-seed="$GROWTH_FUZZ_SEED" -runs="${fixed_runs[$t]}")
  fi
  if "$asan_build/fuzz/fuzz_$t" "$corpus" "fuzz/corpus/$t" "${fixed[@]}" -max_total_time="$seconds" -timeout=25 \
       -rss_limit_mb=2048 -max_len="${max_len[$t]}" -artifact_prefix="$artifacts/" -print_final_stats=1 \
       >"$log" 2>&1; then
    grep -E '^stat::(number_of_executed_units|peak_rss_mb|new_units_added)' "$log" | tr '\n' ' '
    echo "($((SECONDS - start)) s)"
  else
    status=1
    echo "fuzz.sh: fuzz_$t found a failure after $((SECONDS - start)) s:" >&2
    grep -vE '^(#[0-9]+|\s*NEW_FUNC)' "$log" | tail -n 80 >&2
    echo "fuzz.sh: input saved in $artifacts/; replay with $asan_build/fuzz/fuzz_$t <input>" >&2
  fi
done
exit $status
