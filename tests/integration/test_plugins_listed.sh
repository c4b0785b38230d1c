#!/usr/bin/env bash
# meshlabserver loads both plugins and lists all their filters with all their parameters.
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 2000 --seed 1 -o "$work/cloud.ply" >/dev/null
mlserver -d "$work/dump.txt" > "$work/server.log" 2>&1 || { cat "$work/server.log"; fail "meshlabserver -d failed"; }

for plugin in spherepack g2s; do
  so="$GROWTH_BUILD_DIR/plugins/libfilter_$plugin.so"
  "$GROWTH_BUILD_DIR/plugin_params" "$so" "$work/cloud.ply" > "$work/$plugin.params" \
    || fail "plugin_params cannot load $so"
  [ -s "$work/$plugin.params" ] || fail "$so declares no parameters"
  grep -qF "\\section" "$work/dump.txt" || fail "empty dump"
  # Each filter of the plugin (the Sphere Packing plugin has two), with its own parameters.
  cut -f1 "$work/$plugin.params" | awk '!seen[$0]++' > "$work/$plugin.filters"
  while IFS= read -r filter; do
    # The filter's section of the dump: from its \section line to the next one.
    awk -v f="$filter" 'index($0, "\\section") && index($0, f) {on=1; print; next}
                        index($0, "\\section") {on=0} on' "$work/dump.txt" > "$work/section"
    [ -s "$work/section" ] || fail "meshlabserver does not list '$filter'"
    n=0
    while IFS=$'\t' read -r f name type desc; do
      [ "$f" = "$filter" ] || continue
      grep -qF "$desc" "$work/section" || fail "'$filter' is listed without its parameter $name ($desc)"
      n=$((n + 1))
    done < "$work/$plugin.params"
    echo "ok: '$filter' listed with $n parameters"
  done < "$work/$plugin.filters"
done
