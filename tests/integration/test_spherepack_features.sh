#!/usr/bin/env bash
# Keep features through meshlabserver: a box cloud (2 x 1.5 x 1, exact normals) meshed by
# scripts/mlx/spherepack.mlx with keepFeatures on. The filter logs 12 crease lines and 8 corners,
# the mesh is closed and manifold with every edge at least d, and every corner of the box has a
# vertex within 0.05 d.
source "$(dirname "$0")/meshlab_prefix.sh"
source "$(dirname "$0")/mesher_checks.sh"

python3 - "$work/box.ply" <<'PY'
import random, sys
random.seed(7)
half = (1.0, 0.75, 0.5)
area = [4 * half[1] * half[2], 4 * half[0] * half[2], 4 * half[0] * half[1]]
n, total = 30000, 2 * sum(area)
rows = []
for f in range(6):
    ax, sign = f // 2, (1.0 if f % 2 else -1.0)
    for _ in range(round(n * area[ax] / total)):
        p = [h * random.uniform(-1, 1) for h in half]
        p[ax] = sign * half[ax]
        nn = [0.0, 0.0, 0.0]
        nn[ax] = sign
        rows.append("%.9g %.9g %.9g %g %g %g" % (*p, *nn))
with open(sys.argv[1], "w") as out:
    out.write("ply\nformat ascii 1.0\nelement vertex %d\n" % len(rows))
    out.write("".join("property float %s\n" % c for c in ("x", "y", "z", "nx", "ny", "nz")))
    out.write("end_header\n" + "\n".join(rows) + "\n")
PY
cp "$GROWTH_SOURCE_DIR/scripts/mlx/spherepack.mlx" "$work/features.mlx"
sed -i 's|name="keepFeatures" value="false"|name="keepFeatures" value="true"|' "$work/features.mlx"
grep -q 'name="keepFeatures" value="true"' "$work/features.mlx" || fail "could not turn keepFeatures on"
mlserver -i box.ply -o mesh.ply -s features.mlx > "$work/server.log" 2>&1 \
  || { cat "$work/server.log"; fail "meshlabserver failed with keepFeatures"; }
grep -q "keep features (crease angle 30 degrees): [0-9]* crease points, 12 crease lines, 8 corners" "$work/server.log" \
  || { grep "Sphere Packing" "$work/server.log"; fail "not 12 crease lines and 8 corners in the log"; }
d=$(sed -n 's/.*Sphere Packing: .* d = \([0-9.eE+-]*\),.*/\1/p' "$work/server.log" | head -1)
[ -n "$d" ] || fail "no d in the filter's log"
"$GROWTH_BUILD_DIR/mesh_measures" "$work/mesh.ply" > "$work/mesh.json" || fail "mesh_measures failed"
python3 - "$work/mesh.json" "$work/mesh.ply" "$d" <<'PY' || fail "defects in the box mesh"
import json, struct, sys
m, d = json.load(open(sys.argv[1])), float(sys.argv[3])
data = open(sys.argv[2], "rb").read()
head, body = data.split(b"end_header\n", 1)
nv = int([l for l in head.decode().splitlines() if l.startswith("element vertex")][0].split()[2])
assert b"binary_little_endian" in head and b"property float x" in head
props = [l for l in head.decode().splitlines() if l.startswith("property") and "list" not in l
         and head.decode().index(l) < head.decode().index("element face")]
stride = 4 * len(props)
verts = [struct.unpack_from("<3f", body, i * stride) for i in range(nv)]
worst = 0.0
for c in range(8):
    x = (1.0 if c & 1 else -1.0, 0.75 if c & 2 else -0.75, 0.5 if c & 4 else -0.5)
    worst = max(worst, min(sum((a - b) ** 2 for a, b in zip(v, x)) ** 0.5 for v in verts))
checks = [
    ("closed", m["boundary_edges"] == 0),
    ("no non-manifold edges", m["non_manifold_edges"] == 0),
    ("no non-manifold vertices", m["non_manifold_vertices"] == 0),
    ("Euler characteristic 2", m["euler_characteristic"] == 2),
    ("every edge >= d (float storage)", m["edge_min"] >= d * (1 - 1e-5)),
    ("every corner within 0.05 d of a vertex", worst < 0.05 * d),
]
bad = [name for name, ok in checks if not ok]
if bad:
    print("FAIL: " + "; ".join(bad) + "\nworst corner %.4f d\n" % (worst / d) + json.dumps(m, indent=1))
    sys.exit(1)
print("ok: %d vertices, closed, worst corner %.4f d, smallest edge %.9g >= d = %.9g" % (nv, worst / d, m["edge_min"], d))
PY
