#!/usr/bin/env bash
# Bad input to the sphere packer inside MeshLab: each fails with a clear message in the log, the
# script stops and nothing is saved (the filter adds its layer only on success).
source "$(dirname "$0")/meshlab_prefix.sh"

cp "$GROWTH_SOURCE_DIR/scripts/mlx/spherepack.mlx" "$work/spherepack.mlx"
"$GROWTH_BUILD_DIR/make_cloud" --shape sphere --points 3000 --seed 4 -o "$work/cloud.ply" >/dev/null

python3 - "$work" <<'PY'
import math, random, sys
w = sys.argv[1]
random.seed(1)
pts = []
for i in range(2000):
    z = random.uniform(-1, 1); t = random.uniform(0, 2 * math.pi); r = math.sqrt(1 - z * z)
    pts.append((r * math.cos(t), r * math.sin(t), z))
def write(name, rows, normals):
    with open("%s/%s" % (w, name), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % len(rows))
        if normals: f.write("property float nx\nproperty float ny\nproperty float nz\n")
        f.write("end_header\n")
        for p in rows: f.write(" ".join(str(x) for x in p) + "\n")
write("nonormals.ply", pts, False)
write("nan.ply", [p + p for p in pts[:-1]] + [("nan", 0, 0, 0, 0, 1)], True)
write("identical.ply", [(0.5, 0.5, 0.5, 0, 0, 1)] * 50, True)
write("empty.ply", [], True)
PY

# A script with d set to an absolute value (and a maximum that admits it).
script_with_d() {
  sed "s/name=\"sphereDiameter\" value=\"[^\"]*\" min=\"0\" max=\"[^\"]*\"/name=\"sphereDiameter\" value=\"$1\" min=\"0\" max=\"1000\"/" \
    "$work/spherepack.mlx" > "$work/$2"
  grep -q "value=\"$1\"" "$work/$2" || fail "could not set d in the script"
}
script_with_d 100 big.mlx
script_with_d 0.00001 tiny.mlx
# The filter twice: the second run gets the first one's mesh as its current layer.
python3 - "$work" <<'PY'
import sys
w = sys.argv[1]
s = open(w + "/spherepack.mlx").read()
i, j = s.index(" <filter"), s.index("</filter>") + len("</filter>")
open(w + "/twice.mlx", "w").write(s[:j] + "\n" + s[i:j] + s[j:])
PY

expect_failure() { # <name> <input> <script> <message part>
  local name=$1 input=$2 script=$3 message=$4
  rm -f "$work/$name.out.ply"
  if mlserver -i "$input" -o "$name.out.ply" -s "$script" > "$work/$name.log" 2>&1; then
    cat "$work/$name.log"; fail "$name: meshlabserver succeeded"
  fi
  grep -q "Sphere Packing: .*$message" "$work/$name.log" || { cat "$work/$name.log"; fail "$name: no message '$message'"; }
  grep -q "Problem with filter\|Failed to apply" "$work/$name.log" || fail "$name: the script did not stop"
  [ ! -e "$work/$name.out.ply" ] || fail "$name: a mesh was saved"
  echo "ok: $name -> $(grep -o "LOG: 1 Sphere Packing: .*" "$work/$name.log" | head -1 | cut -c1-110)"
}

expect_failure empty empty.ply spherepack.mlx "no vertices"
expect_failure no-normals nonormals.ply spherepack.mlx "Compute normals for point sets"
expect_failure nan nan.ply spherepack.mlx "NaN"
expect_failure identical identical.ply spherepack.mlx "identical"
expect_failure d-larger-than-the-cloud cloud.ply big.mlx "larger than the cloud"
expect_failure d-too-small cloud.ply tiny.mlx "too small for this cloud: the mesh would have about"
expect_failure mesh-not-cloud cloud.ply twice.mlx "is a mesh"
