# Sourced by the MeshLab 2025.07 integration tests after meshlab_prefix.sh. GROWTH_ML2025_PRECISION
# (set by ctest) picks the build: d (default) for PyMeshLab 2025.7 (double, linked against the wheel),
# f for the single-precision MeshLab 2025.07 GUI. Skips the test (exit 77, which ctest reports as
# skipped) when that build's plugins are not built. Provides ml_apply, plugins2025, ml_version
# (2025.07d or 2025.07), ml_precision (double or single), same_counts.
ml2025_precision=${GROWTH_ML2025_PRECISION:-d}
case "$ml2025_precision" in
  d) ml2025_dir=${GROWTH_2025D_DIR:-}; ml_precision=double; ml2025_option=GROWTH_MESHLAB_2025D ;;
  f) ml2025_dir=${GROWTH_2025F_DIR:-}; ml_precision=single; ml2025_option=GROWTH_MESHLAB_2025F
     work="$work.float"; rm -rf "$work" && mkdir -p "$work" ;;
  *) fail "GROWTH_ML2025_PRECISION must be d or f, not '$ml2025_precision'" ;;
esac
if [ -z "$ml2025_dir" ] || [ ! -x "$ml2025_dir/ml_apply" ]; then
  echo "SKIP: the MeshLab 2025.07 ($ml_precision precision) plugins are not built (run scripts/setup.sh" \
       "$([ "$ml2025_precision" = d ] && echo --pymeshlab || echo --meshlab-2025), then configure with" \
       "-D$ml2025_option=ON and build)"
  exit 77
fi
ml_version=$(basename "$ml2025_dir"); ml_version=${ml_version#meshlab-}
plugins2025="$ml2025_dir/plugins"
ml_apply() { QT_QPA_PLATFORM=offscreen "$ml2025_dir/ml_apply" "$@"; }

# Counts of the 2025.07 mesh against the 2020.09 (float) one of the same cloud: equal up to 1 %
# (float against double storage of the points may change a few decisions).
same_counts() { # name count2025 count2020
  python3 -c 'import sys; a, b = int(sys.argv[2]), int(sys.argv[3]); sys.exit(0 if abs(a - b) <= 0.01 * b else 1)' "$@" \
    || fail "$1: $2 in MeshLab $ml_version, $3 in MeshLab 2020.09"
  echo "$1: $2 ($ml_version), $3 (2020.09)"
}
