#!/usr/bin/env bash
# Robust G2S through the real meshlabserver: a generated torus meshed with scripts/mlx/g2s.mlx
# (closed, manifold, consistently oriented, per-face quality saved), and bad inputs that must fail
# with a clear message (or give a valid result) without crashing the host.
source "$(dirname "$0")/meshlab_prefix.sh"
source "$(dirname "$0")/mesher_checks.sh"

torus_cloud "$work/torus.ply"
mlserver_mlx g2s torus.ply mesh.ply -m fq
grep -q "Robust G2S: .* faces on" "$work/server.log" || { cat "$work/server.log"; fail "no statistics in the log"; }
for pass in "non-manifold vertices (sec. 4.2)" "crossing faces" "hole closure" "small handles" "orientation"; do
  grep -qF "Robust G2S pass, $pass: " "$work/server.log" || { cat "$work/server.log"; fail "no log line for the pass '$pass'"; }
done
LC_ALL=C sed -n '/^end_header/q;p' "$work/mesh.ply" | grep -q "property float quality" \
  || fail "per-face quality not saved"
check_closed_torus "$work/mesh.ply"
faces=$(faces_of "$work/mesh.ply")
verts=$(vertices_of "$work/mesh.ply")
echo "ok: torus of 20000 points -> $faces faces on $verts vertices, closed and manifold"

# Bad inputs: each must end with our message (or a valid result), never with a crash.
python3 - "$work" <<'PY'
import os, sys
d = sys.argv[1]
def ply(name, pts):
    with open(os.path.join(d, name), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                "property float z\nend_header\n" % len(pts))
        for p in pts:
            f.write("%s %s %s\n" % p)
ply("two.ply", [(0, 0, 0), (1, 0, 0)])
ply("line.ply", [(i, 2 * i, 3 * i) for i in range(50)])
ply("same.ply", [(1, 1, 1)] * 20)
ply("nan.ply", [(0, 0, 0), (1, 0, 0), (0, 1, 0), ("nan", 0, 0)])
ply("sparse.ply", [(0, 0, 0), (1, 0, 0), (100, 0, 0), (100, 1, 0.5)])
ply("plane.ply", [(i * 0.1 + 0.013 * ((i * 7 + j * 3) % 5), j * 0.1 + 0.011 * ((i + 5 * j) % 7), 0)
                  for i in range(30) for j in range(30)])
PY
for case in two line same nan sparse plane; do
  set +e
  mlserver -i "$case.ply" -o "$case.out.ply" -s g2s.mlx > "$work/$case.log" 2>&1
  status=$?
  set -e
  # meshlabserver exits with 255 when a filter refuses its input; 129..254 would be a signal.
  if [ "$status" -gt 128 ] && [ "$status" -lt 255 ]; then
    cat "$work/$case.log"; fail "meshlabserver crashed on '$case' (status $status)"
  fi
  if [ -f "$work/$case.out.ply" ] && [ "$(faces_of "$work/$case.out.ply")" -gt 0 ]; then
    echo "ok: '$case' gives a mesh of $(faces_of "$work/$case.out.ply") faces"
  else
    grep -q "LOG: [0-9] Robust G2S: " "$work/$case.log" || { cat "$work/$case.log"; fail "no Robust G2S message for '$case'"; }
    echo "ok: '$case' refused: $(grep -m1 -o 'LOG: [0-9] Robust G2S: .*' "$work/$case.log" | head -c 200)"
  fi
done
# The coplanar cloud is a valid input: it must give a mesh.
[ -f "$work/plane.out.ply" ] && [ "$(faces_of "$work/plane.out.ply")" -gt 1500 ] || fail "coplanar cloud not meshed"
