# Sourced by the MeshLab 2025.07d integration tests after meshlab_prefix.sh: skips the test (exit 77,
# which ctest reports as skipped) when the build has no 2025.07d plugins, and provides ml_apply.
if [ -z "${GROWTH_2025D_DIR:-}" ] || [ ! -x "$GROWTH_2025D_DIR/ml_apply" ]; then
  echo "SKIP: the MeshLab 2025.07d plugins are not built (run scripts/setup.sh, then configure with" \
       "-DGROWTH_MESHLAB_2025D=ON and build)"
  exit 77
fi
plugins2025="$GROWTH_2025D_DIR/plugins"
ml_apply() { QT_QPA_PLATFORM=offscreen "$GROWTH_2025D_DIR/ml_apply" "$@"; }

# Counts of the 2025.07d (double) mesh against the 2020.09 (float) one of the same cloud: equal up
# to 1 % (float against double storage of the points may change a few decisions).
same_counts() { # name count2025 count2020
  python3 -c 'import sys; a, b = int(sys.argv[2]), int(sys.argv[3]); sys.exit(0 if abs(a - b) <= 0.01 * b else 1)' "$@" \
    || fail "$1: $2 in MeshLab 2025.07d, $3 in MeshLab 2020.09"
  echo "$1: $2 (2025.07d), $3 (2020.09)"
}
