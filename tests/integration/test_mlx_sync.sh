#!/usr/bin/env bash
# scripts/mlx/<filter>.mlx list exactly the parameters the filters declare (names, types, order):
# meshlabserver 2020.09 needs every parameter in a script, so a stale example would break users.
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 2000 --seed 1 -o "$work/cloud.ply" >/dev/null
# Every filter of a plugin is in exactly one script, the script named after the plugin for its first
# filter (spherepack.mlx) and <plugin>_<kind>.mlx for the others (spherepack_remesh.mlx).
for plugin in spherepack g2s; do
  "$GROWTH_BUILD_DIR/plugin_params" --mlx "$GROWTH_BUILD_DIR/plugins/libfilter_$plugin.so" \
    "$work/cloud.ply" > "$work/$plugin.expected.mlx"
  python3 - "$work/$plugin.expected.mlx" "$GROWTH_SOURCE_DIR/scripts/mlx/$plugin.mlx" \
    "$GROWTH_SOURCE_DIR"/scripts/mlx/"$plugin"_*.mlx <<'PY'
import os, sys, xml.etree.ElementTree as ET
def params(path):
    root = ET.parse(path).getroot()
    return [(f.get("name"), [(p.get("name"), p.get("type")) for p in f.findall("Param")])
            for f in root.findall("filter")]
want = params(sys.argv[1])
scripts = [s for s in sys.argv[2:] if os.path.exists(s)]
have = [(s, f) for s in scripts for f in params(s)]
ok = True
for name, plist in want:
    found = [(s, p) for s, (n, p) in have if n == name]
    if len(found) != 1 or found[0][1] != plist:
        print("FAIL: filter %r is out of sync with scripts/mlx.\n  scripts: %s\n  plugin: %s" % (name, found, plist))
        ok = False
    else:
        print("ok: %s lists %d parameters of %r" % (found[0][0], len(plist), name))
for s, (n, p) in have:
    if n not in [w[0] for w in want]:
        print("FAIL: %s names a filter the plugin does not have: %r" % (s, n))
        ok = False
sys.exit(0 if ok else 1)
PY
done
