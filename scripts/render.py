#!/usr/bin/python3
"""Renders a triangle mesh (PLY) to a PNG for the README: the whole mesh, flat shaded, beside a
close-up of a small window with the triangles' edges drawn.

Orthographic view, painter's order (triangles drawn back to front by the depth of their centroid),
two-sided Lambert shading of each face's normal. Needs only Debian's python3-numpy and
python3-matplotlib (scripts/setup.sh installs both).

Usage: scripts/render.py MESH.ply -o OUT.png [--title TEXT] [--view AZIMUTH,ELEVATION]
                         [--window FX,FY,FW] [--width-px W] [--height-px H]

--view      degrees: the camera turns AZIMUTH about the y axis, then ELEVATION up (0,0: looking
            down -z with y up, the Stanford Bunny's front view)
--window    the close-up: its centre (FX, FY) and width FW as fractions of the whole view's
            width and height (0,0 = bottom left)
"""
import argparse
import io
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402
from PIL import Image  # noqa: E402  (python3-pil, a dependency of python3-matplotlib)

PLY_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
             "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
             "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


def read_ply(path):
    """Vertices (n × 3 float64) and triangles (m × 3 int) of a PLY file, ASCII or binary
    little-endian; faces must be triangles (the meshers write only triangles)."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"ply":
            sys.exit("render.py: %s is not a PLY file" % path)
        fmt, elements = None, []
        while True:
            line = f.readline()
            if not line:
                sys.exit("render.py: %s: no end_header" % path)
            words = line.decode("ascii", "replace").split()
            if not words or words[0] in ("comment", "obj_info"):
                continue
            if words[0] == "format":
                fmt = words[1]
            elif words[0] == "element":
                elements.append((words[1], int(words[2]), []))
            elif words[0] == "property":
                elements[-1][2].append(words[1:])
            elif words[0] == "end_header":
                break
        if fmt not in ("ascii", "binary_little_endian"):
            sys.exit("render.py: PLY format %s is not supported" % fmt)
        verts, faces = None, np.zeros((0, 3), dtype=np.int64)
        if fmt == "ascii":
            rows = f.read().decode("ascii").split("\n")
            at = 0
            for name, count, props in elements:
                block = rows[at:at + count]
                at += count
                if name == "vertex":
                    names = [p[-1] for p in props]
                    a = np.array([r.split() for r in block], dtype=np.float64)
                    verts = a[:, [names.index(c) for c in "xyz"]]
                elif name == "face" and count:
                    a = [r.split() for r in block]
                    if any(r[0] != "3" for r in a):
                        sys.exit("render.py: only triangles are supported")
                    faces = np.array([r[1:4] for r in a], dtype=np.int64)
            return verts, faces
        for name, count, props in elements:
            fields = []
            for p in props:
                if p[0] == "list":
                    if count and name == "face":
                        fields += [("n", PLY_TYPES[p[1]]), ("v", "<" + PLY_TYPES[p[2]], (3,))]
                    else:
                        sys.exit("render.py: a list property outside the face element")
                else:
                    fields.append((p[1], "<" + PLY_TYPES[p[0]]))
            a = np.frombuffer(f.read(np.dtype(fields).itemsize * count), dtype=np.dtype(fields), count=count)
            if name == "vertex":
                verts = np.stack([a[c].astype(np.float64) for c in "xyz"], axis=1)
            elif name == "face" and count:
                if np.any(a["n"] != 3):
                    sys.exit("render.py: only triangles are supported")
                faces = a["v"].astype(np.int64)
        return verts, faces


def camera(azimuth_deg, elevation_deg):
    """Rows: the screen's x, y and the viewing direction's opposite (towards the camera)."""
    a, e = np.radians(azimuth_deg), np.radians(elevation_deg)
    ry = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    rx = np.array([[1, 0, 0], [0, np.cos(e), -np.sin(e)], [0, np.sin(e), np.cos(e)]])
    return rx @ ry


def draw(ax, p, faces, shade, edges, xlim, ylim):
    """Triangles of screen positions p (x, y, depth towards the camera), back to front."""
    tri = p[faces]
    lo, hi = tri[:, :, :2].min(axis=1), tri[:, :, :2].max(axis=1)
    keep = (hi[:, 0] >= xlim[0]) & (lo[:, 0] <= xlim[1]) & (hi[:, 1] >= ylim[0]) & (lo[:, 1] <= ylim[1])
    tri, s = tri[keep], shade[keep]
    order = np.argsort(tri[:, :, 2].mean(axis=1), kind="stable")
    base = np.array([0.62, 0.70, 0.80])
    colors = np.clip(base[None, :] * s[order, None], 0, 1)
    if edges:
        coll = PolyCollection(tri[order, :, :2], facecolors=colors, edgecolors=(0.12, 0.12, 0.15),
                              linewidths=0.35, antialiaseds=True)
    else:  # edges in the face colour close the hairline cracks between neighbours
        coll = PolyCollection(tri[order, :, :2], facecolors=colors, edgecolors=colors, linewidths=0.15,
                              antialiaseds=False)
    ax.add_collection(coll)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    return int(keep.sum())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("--view", default="0,0")
    ap.add_argument("--window", default="0.5,0.5,0.12")
    ap.add_argument("--width-px", type=int, default=960)
    ap.add_argument("--height-px", type=int, default=470)
    args = ap.parse_args()

    verts, faces = read_ply(args.mesh)
    if faces.shape[0] == 0:
        sys.exit("render.py: %s has no faces" % args.mesh)
    rot = camera(*[float(x) for x in args.view.split(",")])
    p = (verts - verts.mean(axis=0)) @ rot.T
    e1, e2 = verts[faces[:, 1]] - verts[faces[:, 0]], verts[faces[:, 2]] - verts[faces[:, 0]]
    n = np.cross(e1, e2) @ rot.T
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    light = np.array([-0.35, 0.45, 1.0])
    light /= np.linalg.norm(light)
    shade = 0.28 + 0.72 * np.abs(n @ light)  # two-sided: the picture does not depend on orientation

    used = np.unique(faces)
    lo, hi = p[used, :2].min(axis=0), p[used, :2].max(axis=0)
    pad = 0.03 * (hi - lo).max()
    lo, hi = lo - pad, hi + pad
    fx, fy, fw = [float(x) for x in args.window.split(",")]
    cx, cy = lo + (hi - lo) * np.array([fx, fy])
    half = 0.5 * fw * (hi - lo)[0]

    dpi = 100
    fig = plt.figure(figsize=(args.width_px / dpi, args.height_px / dpi), dpi=dpi)
    top = 0.9 if args.title else 0.98
    ax_full = fig.add_axes([0.01, 0.02, 0.48, top - 0.02])
    ax_zoom = fig.add_axes([0.51, 0.02, 0.48, top - 0.02])
    draw(ax_full, p, faces, shade, False, (lo[0], hi[0]), (lo[1], hi[1]))
    ax_full.add_patch(Rectangle((cx - half, cy - half), 2 * half, 2 * half, fill=False, edgecolor="#c0392b",
                                linewidth=1.4))
    shown = draw(ax_zoom, p, faces, shade, True, (cx - half, cx + half), (cy - half, cy + half))
    for sp in ax_zoom.spines.values():
        sp.set_edgecolor("#c0392b")
        sp.set_linewidth(1.4)
    for sp in ax_full.spines.values():
        sp.set_visible(False)
    if args.title:
        fig.suptitle(args.title, fontsize=11, y=0.975)
    # A palette of 128 colours keeps the PNG small (the shading needs no more) for the repository.
    buf = io.BytesIO()
    fig.savefig(buf, dpi=dpi, format="png")
    buf.seek(0)
    Image.open(buf).convert("RGB").quantize(colors=128, method=Image.Quantize.MEDIANCUT).save(
        args.out, optimize=True)
    print("render.py: %s: %d vertices, %d faces, %d in the close-up -> %s"
          % (args.mesh, len(used), faces.shape[0], shown, args.out))


if __name__ == "__main__":
    main()
