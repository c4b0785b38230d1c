#!/usr/bin/env bash
# scripts/render.py, which draws the README's pictures: it reads the meshes both engines write
# (binary PLY, with and without face quality) and an ASCII PLY, draws every face (its count must
# match the file's; the close-up holds some), writes a PNG of the asked size that is not blank and stays small, and refuses
# what is not a triangle mesh. The committed pictures in docs/images/ stay under 300 KB each.
source "$(dirname "$0")/meshlab_prefix.sh"

render="$GROWTH_SOURCE_DIR/scripts/render.py"
python=/usr/bin/python3
"$python" -c "import numpy, matplotlib, PIL" 2>/dev/null || { echo "SKIP: python3-numpy/matplotlib missing"; exit 77; }

"$GROWTH_BUILD_DIR/make_cloud" --shape torus --points 4000 --seed 1 -o "$work/torus.ply" >/dev/null
"$GROWTH_BUILD_DIR/g2s_run" "$work/torus.ply" -o "$work/g2s.ply" >/dev/null 2>&1 || fail "g2s_run failed"
"$GROWTH_BUILD_DIR/spherepack_run" "$work/torus.ply" -o "$work/spherepack.ply" >/dev/null 2>&1 \
  || fail "spherepack_run failed"

# An ASCII copy of the sphere packer's mesh: the same faces through the reader's other branch.
"$python" - "$work/spherepack.ply" "$work/ascii.ply" <<'PY' || fail "could not write the ASCII copy"
import os, sys
sys.path.insert(0, os.path.join(os.environ["GROWTH_SOURCE_DIR"], "scripts"))
import render
v, f = render.read_ply(sys.argv[1])
with open(sys.argv[2], "w") as out:
    out.write("ply\nformat ascii 1.0\ncomment copy\nelement vertex %d\nproperty float x\nproperty float y\n"
              "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face %d\n"
              "property list uchar int vertex_indices\nend_header\n" % (len(v), len(f)))
    out.writelines("%.9g %.9g %.9g 0 0 1\n" % tuple(p) for p in v)
    out.writelines("3 %d %d %d\n" % tuple(t) for t in f)
PY

check_png() {  # check_png MESH PNG: the face count printed, the size, not blank, small
  local mesh=$1 png=$2 log=$work/$(basename "$2").log
  "$python" "$render" "$mesh" -o "$png" --title "test" --window 0.5,0.85,0.15 --width-px 640 --height-px 320 \
    > "$log" 2>&1 || fail "render.py failed on $mesh: $(cat "$log")"
  grep -q ", $(faces_of "$mesh") faces," "$log" || fail "render.py did not read all of $(faces_of "$mesh") faces: $(cat "$log")"
  # The window (the top of the torus's ring, seen from +z) holds a few hundred faces.
  local close=$(sed -n 's/.* faces, \([0-9]*\) in the close-up.*/\1/p' "$log")
  [ "${close:-0}" -ge 50 ] || fail "only ${close:-no} faces in the close-up: $(cat "$log")"
  "$python" - "$png" <<'PY' || fail "$png: wrong size, blank or too large"
import os, sys
from PIL import Image
im = Image.open(sys.argv[1]).convert("RGB")
assert im.size == (640, 320), im.size
px = im.getdata()
inked = sum(1 for p in px if sum(p) < 600) / len(px)   # not white: the mesh, its edges, the frame
assert 0.15 < inked < 0.9, inked
assert os.path.getsize(sys.argv[1]) < 300 * 1024, os.path.getsize(sys.argv[1])
PY
}
check_png "$work/g2s.ply" "$work/g2s.png"
check_png "$work/spherepack.ply" "$work/spherepack.png"
check_png "$work/ascii.ply" "$work/ascii.png"

# Not a triangle mesh: refused with a message, no picture.
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n' > "$work/quad.ply"
if "$python" "$render" "$work/quad.ply" -o "$work/quad.png" > "$work/quad.log" 2>&1; then fail "a quad was accepted"; fi
grep -q "only triangles" "$work/quad.log" || fail "no message for a quad: $(cat "$work/quad.log")"
[ ! -e "$work/quad.png" ] || fail "a picture was written for a quad"
"$python" "$render" "$work/torus.ply" -o "$work/cloud.png" > "$work/cloud.log" 2>&1 && fail "a cloud without faces was accepted"
grep -q "no faces" "$work/cloud.log" || fail "no message for a cloud: $(cat "$work/cloud.log")"

for png in "$GROWTH_SOURCE_DIR"/docs/images/*.png; do
  [ "$(stat -c %s "$png")" -lt $((300 * 1024)) ] || fail "$png is larger than 300 KB"
done
echo "PASS"
