#!/usr/bin/env bash
# scripts/mlx/<filter>.mlx list exactly the parameters the filters declare (names, types, order):
# meshlabserver 2020.09 needs every parameter in a script, so a stale example would break users.
source "$(dirname "$0")/meshlab_prefix.sh"

"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 2000 --seed 1 -o "$work/cloud.ply" >/dev/null
for plugin in spherepack g2s; do
  "$GROWTH_BUILD_DIR/plugin_params" --mlx "$GROWTH_BUILD_DIR/plugins/libfilter_$plugin.so" \
    "$work/cloud.ply" > "$work/$plugin.expected.mlx"
  python3 - "$GROWTH_SOURCE_DIR/scripts/mlx/$plugin.mlx" "$work/$plugin.expected.mlx" <<'PY'
import sys, xml.etree.ElementTree as ET
def params(path):
    root = ET.parse(path).getroot()
    return [(f.get("name"), [(p.get("name"), p.get("type")) for p in f.findall("Param")])
            for f in root.findall("filter")]
have, want = params(sys.argv[1]), params(sys.argv[2])
if have != want:
    print("FAIL: %s is out of sync with the plugin.\n  script: %s\n  plugin: %s" % (sys.argv[1], have, want))
    sys.exit(1)
print("ok: %s lists %d parameters" % (sys.argv[1], len(want[0][1])))
PY
done
