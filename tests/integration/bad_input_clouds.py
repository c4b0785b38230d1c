#!/usr/bin/env python3
"""The clouds of the bad-input matrix (tests/integration/test_bad_input_matrix.sh), the check that a
layer MeshLab saved is the input, bit for bit, and a shift that brings a geo-referenced mesh back
to the origin for measuring.

    bad_input_clouds.py write DIR          writes DIR/<case>.ply for every case, prints the names
    bad_input_clouds.py same IN.ply OUT.ply exit 0 when OUT has IN's vertices and normals, bit for bit
    bad_input_clouds.py shift IN.ply OUT.ply DX DY DZ
                                           OUT = IN (binary little-endian, float x y z) with every
                                           vertex moved by -(DX, DY, DZ); exact when the differences
                                           are floats (as for the offset-1e6 case)

Plain python3 (no numpy). The clouds are binary little-endian PLY with float x y z nx ny nz (what
MeshLab 2020.09 stores), so that the values MeshLab reads are known exactly. Fixed seeds.
"""
import math
import random
import struct
import sys

N = 3000  # points of the base clouds: small, so that the whole matrix stays fast


def sphere(n, seed, radius=1.0, centre=(0.0, 0.0, 0.0)):
    """n points uniform on a sphere, with their outward normals."""
    rnd = random.Random(seed)
    rows = []
    for _ in range(n):
        z = rnd.uniform(-1, 1)
        t = rnd.uniform(0, 2 * math.pi)
        r = math.sqrt(1 - z * z)
        nx, ny, nz = r * math.cos(t), r * math.sin(t), z
        rows.append((centre[0] + radius * nx, centre[1] + radius * ny, centre[2] + radius * nz, nx, ny, nz))
    return rows


def uv_sphere(per_ring):
    """A latitude-longitude sampling of the unit sphere: equal steps in latitude and longitude
    (360° / per_ring), rings from pole to pole and the two poles, as a UV-sphere generator or a
    turntable scan gives. Every ring point is a neighbour of its pole."""
    rows = [(0.0, 0.0, 1.0, 0.0, 0.0, 1.0), (0.0, 0.0, -1.0, 0.0, 0.0, -1.0)]
    rings = per_ring // 2 - 1
    for i in range(1, rings + 1):
        theta = 2 * math.pi * i / per_ring
        for j in range(per_ring):
            phi = 2 * math.pi * j / per_ring
            p = (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))
            rows.append(p + p)
    return rows


def cube_point(i, j, k, n):
    """Lattice point (i, j, k) / 32 on the surface of the cube [0, n/32]^3, with the mean of the
    outward normals of the faces it lies on."""
    nrm = [(-1 if a == 0 else 1 if a == n else 0) for a in (i, j, k)]
    length = math.sqrt(sum(x * x for x in nrm))
    return (i / 32.0, j / 32.0, k / 32.0) + tuple(x / length for x in nrm)


def unit(rnd):
    while True:
        v = [rnd.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        if n > 1e-3:
            return tuple(x / n for x in v)


def cases():
    """name -> (rows, faces). rows are (x, y, z, nx, ny, nz)."""
    base = sphere(N, 1)
    rnd = random.Random(7)
    c = {}
    c["empty"] = []
    c["one-point"] = base[:1]
    c["two-points"] = base[:2]
    c["three-points"] = [(0, 0, 0, 0, 0, 1), (1, 0, 0, 0, 0, 1), (0, 1, 0, 0, 0, 1)]
    c["nan"] = base + [(float("nan"), 0, 0, 0, 0, 1)]
    c["inf"] = base + [(0, float("inf"), 0, 0, 0, 1)]
    c["identical"] = [(0.5, 0.5, 0.5, 0, 0, 1)] * 50
    c["duplicates"] = base + base[:N // 3]  # a third of the points twice, exactly
    c["collinear"] = [(0.01 * i, 0.02 * i, -0.03 * i, 0.0, 0.8320502943378437, 0.5547001962252291)
                      for i in range(200)]
    c["coplanar"] = [(rnd.uniform(-1, 1), rnd.uniform(-1, 1), 0.0, 0, 0, 1) for _ in range(N)]
    # An exact lattice (1/32 is exact in float): four points on every empty circle.
    c["regular-grid"] = [(i / 32.0, j / 32.0, 0.0, 0, 0, 1) for i in range(55) for j in range(55)]
    # The surface of a cube on the same lattice: exact ties in 3D, and sharp edges and corners.
    c["cube-lattice"] = [cube_point(i, j, k, 24) for i in range(25) for j in range(25) for k in range(25)
                         if {i, j, k} & {0, 24}]
    # 149 rings of 300 points and the poles (44,702 points): 300 edges at each pole, more than 255
    # neighbours at one point.
    c["uv-sphere"] = uv_sphere(300)
    c["far-outlier"] = base + [(1e4, 0, 0, 1, 0, 0)]
    # At 20k points the far point costs G2S today (holes, time): see the matrix's notes.
    c["far-outlier-20k"] = sphere(20000, 2) + [(1e4, 0, 0, 1, 0, 0)]
    c["far-outliers"] = base + [(1e4 * x, 1e4 * y, 1e4 * z, x, y, z) for x, y, z in
                                [unit(rnd) for _ in range(5)]]
    c["outliers-20pct"] = base + [tuple(rnd.uniform(-1.5, 1.5) for _ in range(3)) + unit(rnd)
                                  for _ in range(N // 5)]
    # Geo-referenced: a 20 m object 1e6 m from the origin; in float the coordinates step by 1/16.
    c["offset-1e6"] = sphere(N, 1, radius=10.0, centre=(1e6, 1e6, 1e6))
    c["tiny-1e-6"] = sphere(N, 1, radius=0.5e-6)
    c["flipped-normals"] = [r if rnd.random() < 0.5 else r[:3] + tuple(-x for x in r[3:]) for r in base]
    c["zero-normals"] = [r if i % 10 else r[:3] + (0.0, 0.0, 0.0) for i, r in enumerate(base)]
    c["nan-normal"] = base[:-1] + [base[-1][:3] + (float("nan"), 0.0, 1.0)]
    octahedron = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    c["mesh"] = ([p + p for p in octahedron],
                 [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)])
    return {k: (v if isinstance(v, tuple) else (v, [])) for k, v in c.items()}


def write_ply(path, rows, faces):
    with open(path, "wb") as f:
        head = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                "property float x\nproperty float y\nproperty float z\n"
                "property float nx\nproperty float ny\nproperty float nz\n" % len(rows))
        if faces:
            head += "element face %d\nproperty list uchar int vertex_indices\n" % len(faces)
        f.write((head + "end_header\n").encode("ascii"))
        for r in rows:
            f.write(struct.pack("<6f", *[float(x) for x in r]))
        for t in faces:
            f.write(struct.pack("<B3i", 3, *t))


PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
             "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
             "float": "f", "float32": "f", "double": "d", "float64": "d"}


def read_vertices(path):
    """The vertex element of a PLY file (binary little-endian or ascii): a list of dicts, keyed by
    property name, of the raw values (floats as stored, compared bit for bit)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    fmt, count, props, in_vertex = None, 0, [], False
    for line in header:
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            in_vertex = w[1] == "vertex"
            if in_vertex:
                count = int(w[2])
            elif not props and count == 0:
                raise SystemExit("%s: an element before the vertices" % path)
        elif w[0] == "property" and in_vertex:
            if w[1] == "list":
                raise SystemExit("%s: list property in the vertex element" % path)
            props.append((w[2], PLY_TYPES[w[1]]))
    rows = []
    if fmt == "ascii":
        lines = data[end:].decode("ascii").split("\n")
        for i in range(count):
            vals = lines[i].split()
            rows.append({name: struct.unpack("<" + t, struct.pack("<" + t, float(v) if t in "fd" else int(v)))[0]
                         for (name, t), v in zip(props, vals)})
    elif fmt == "binary_little_endian":
        rec = "<" + "".join(t for _, t in props)
        size = struct.calcsize(rec)
        for i in range(count):
            vals = struct.unpack_from(rec, data, end + i * size)
            rows.append(dict(zip((n for n, _ in props), vals)))
    else:
        raise SystemExit("%s: unsupported PLY format %s" % (path, fmt))
    return rows


def bits(v):
    return struct.pack("<f", v)


def same(inp, out):
    a, b = read_vertices(inp), read_vertices(out)
    if len(a) != len(b):
        print("the saved input layer has %d vertices, the input %d" % (len(b), len(a)))
        return 1
    keys = ("x", "y", "z", "nx", "ny", "nz")
    for k in keys:
        if a and k in a[0] and k not in b[0]:
            print("the saved input layer has no property %s" % k)
            return 1
    for i, (p, q) in enumerate(zip(a, b)):
        for k in keys:
            if k in p and bits(p[k]) != bits(q[k]):
                print("vertex %d: %s is %r in the saved input layer, %r in the input" % (i, k, q[k], p[k]))
                return 1
    return 0


def shift(inp, out, offset):
    with open(inp, "rb") as f:
        data = bytearray(f.read())
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in header:
        raise SystemExit("%s: not binary little-endian" % inp)
    count, props, in_vertex = 0, [], False
    for line in header:
        w = line.split()
        if w and w[0] == "element":
            in_vertex = w[1] == "vertex"
            if in_vertex:
                count = int(w[2])
        elif w and w[0] == "property" and in_vertex:
            props.append((w[-1], PLY_TYPES[w[-2]] if w[1] != "list" else None))
    if any(t is None for _, t in props):
        raise SystemExit("%s: list property in the vertex element" % inp)
    rec = "<" + "".join(t for _, t in props)
    size = struct.calcsize(rec)
    at = {name: struct.calcsize("<" + "".join(t for _, t in props[:i])) for i, (name, _) in enumerate(props)}
    for k, name in enumerate(("x", "y", "z")):
        if dict(props).get(name) != "f":
            raise SystemExit("%s: %s is not a float" % (inp, name))
        for i in range(count):
            o = end + i * size + at[name]
            v = struct.unpack_from("<f", data, o)[0] - offset[k]
            struct.pack_into("<f", data, o, v)
            if struct.unpack_from("<f", data, o)[0] != v:
                raise SystemExit("%s: vertex %d: %s - offset is not a float" % (inp, i, name))
    with open(out, "wb") as f:
        f.write(data)
    return 0


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "write":
        for name, (rows, faces) in cases().items():
            write_ply("%s/%s.ply" % (sys.argv[2], name), rows, faces)
            print(name)
        return 0
    if len(sys.argv) == 4 and sys.argv[1] == "same":
        return same(sys.argv[2], sys.argv[3])
    if len(sys.argv) == 7 and sys.argv[1] == "shift":
        return shift(sys.argv[2], sys.argv[3], [float(x) for x in sys.argv[4:7]])
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main())
