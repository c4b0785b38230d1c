#!/usr/bin/env bash
# meshlabserver loads both plugins and lists both filters with all their parameters.
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 2000 --seed 1 -o "$work/cloud.ply" >/dev/null
mlserver -d "$work/dump.txt" > "$work/server.log" 2>&1 || { cat "$work/server.log"; fail "meshlabserver -d failed"; }

for plugin in spherepack g2s; do
  so="$GROWTH_BUILD_DIR/plugins/libfilter_$plugin.so"
  "$GROWTH_BUILD_DIR/plugin_params" "$so" "$work/cloud.ply" > "$work/$plugin.params" \
    || fail "plugin_params cannot load $so"
  [ -s "$work/$plugin.params" ] || fail "$so declares no parameters"
  filter=$(cut -f1 "$work/$plugin.params" | head -1)
  grep -qF "\\section" "$work/dump.txt" || fail "empty dump"
  # The filter's section of the dump: from its \section line to the next one.
  awk -v f="$filter" 'index($0, "\\section") && index($0, f) {on=1; print; next}
                      index($0, "\\section") {on=0} on' "$work/dump.txt" > "$work/$plugin.section"
  [ -s "$work/$plugin.section" ] || fail "meshlabserver does not list '$filter'"
  while IFS=$'\t' read -r _ name type desc; do
    grep -qF "$desc" "$work/$plugin.section" || fail "'$filter' is listed without its parameter $name ($desc)"
  done < "$work/$plugin.params"
  echo "ok: '$filter' listed with $(wc -l < "$work/$plugin.params") parameters"
done
