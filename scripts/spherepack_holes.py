#!/usr/bin/env python3
"""Holes of Sphere Packing on clean closed clouds with estimated normals: a matrix of cells.

Each cell is a closed shape of build/make_cloud (sphere, torus, genus2, hollowball, latlong, and the
slab as a box with sharp edges: "slab" is 0.4 thick, "thinslab" 0.05, thinner than d from about 2
mean spacings on, so that its two sides cannot both be meshed), sampled uniformly or not
(--nonuniform, 4:1 along z; latlong is a fixed grid), with the normals estimated as MeshLab's
"Compute normals for point sets" does (make_cloud --estimate-normals 10: PCA over the 10 nearest
points, signs propagated over the neighbour graph, not always consistent), meshed by
build/spherepack_run at d = K mean spacings (--d-spacings K: K times the mean nearest-neighbour
distance, growth::meanSpacing), once with the hole pass and once without it (--no-hole-pass).
Extra clouds (PLY with normals, e.g. a real scan with MeshLab's normals) are added with --cloud.

Per cell: the boundary loops of the output with and without the pass, and why the loops seen
before the pass were open (regions left open by sec. 3.7's border limit or ear cut, faces removed
by the manifold and intersection clean-up, small pieces dropped) and why loops stay open after it
(the pass's counters: too long, not triangulable, not covered by the cloud, folded, crossing).

  scripts/spherepack_holes.py [--build build] [--points 30000] [--seed 1] [--d 1.5,2,2.5,3,4,6,8,10]
      [--shapes sphere,torus,genus2,hollowball,slab,thinslab,latlong] [--density-ratio 4]
      [--cloud file.ply ...] [--out table.md]
"""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    kv = {}
    for line in out.splitlines():
        if ": " in line and not line.startswith("warning"):
            k, v = line.split(": ", 1)
            kv[k] = v
    return kv


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--points", type=int, default=30000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--k", type=int, default=10, help="neighbours of the normal estimate")
    ap.add_argument("--d", default="1.5,2,2.5,3,4,6,8,10")
    ap.add_argument("--shapes", default="sphere,torus,genus2,hollowball,slab,thinslab,latlong")
    ap.add_argument("--density-ratio", type=float, default=4.0, help="of the non-uniform sampling")
    ap.add_argument("--cloud", action="append", default=[], help="an extra PLY cloud with normals")
    ap.add_argument("--out", help="also write the table here (markdown)")
    a = ap.parse_args()
    make_cloud = os.path.join(a.build, "make_cloud")
    packer = os.path.join(a.build, "spherepack_run")
    ds = [float(x) for x in a.d.split(",")]
    rows = []
    header = ("| cloud | d (mean spacings) | loops before | regions left open | faces removed | pieces dropped "
              "| loops after | closed | faces added | why open after (long/tri/cover/fold/cross/other) "
              "| smallest edge / d | manifold | seconds before / after |")
    lines = [header, "|" + "|".join("---" for _ in range(header.count("|") - 1)) + "|"]
    with tempfile.TemporaryDirectory() as tmp:
        clouds = []
        for shape in a.shapes.split(","):
            for nonuniform in ([False] if shape == "latlong" else [False, True]):
                name = shape + ("-nonuniform" if nonuniform else "")
                path = os.path.join(tmp, name + ".ply")
                cmd = [make_cloud, "--shape", "slab" if shape == "thinslab" else shape, "--points", str(a.points),
                       "--seed", str(a.seed), "--estimate-normals", str(a.k), "-o", path]
                if shape == "slab":
                    cmd += ["--thickness", "0.4"]
                if nonuniform:
                    cmd += ["--nonuniform", "--density-ratio", str(a.density_ratio)]
                subprocess.run(cmd, check=True, capture_output=True)
                clouds.append((name, path))
        for path in a.cloud:
            clouds.append((os.path.basename(path), path))
        for name, path in clouds:
            for d in ds:
                base = run([packer, path, "--d-spacings", str(d), "--no-hole-pass"])
                after = run([packer, path, "--d-spacings", str(d), "--measure"])
                why = "/".join(after.get(k, "?") for k in ("holes_too_long", "holes_not_triangulable",
                                                           "holes_not_covered", "holes_folded",
                                                           "holes_crossing", "holes_other"))
                manifold = (after.get("non_manifold_edges") == "0" and
                            after.get("non_manifold_vertices_measured") == "0" and
                            after.get("self_intersecting_pairs") == "0" and
                            after.get("inconsistent_edges") == "0")
                ratio = float(after["smallest_edge"]) / float(after["d"]) if float(after["d"]) > 0 else 0
                row = (f"| {name} | {d:g} | {base['boundary_loops_output']} | {base['regions_left_open']} "
                       f"| {base['faces_removed']} | {base['components_dropped']} | {after['boundary_loops_output']} "
                       f"| {after['holes_closed']} | {after['hole_faces_added']} | {why} | {ratio:.6f} "
                       f"| {'yes' if manifold else 'NO'} | {base['seconds']} / {after['seconds']} |")
                rows.append((name, d, int(base["boundary_loops_output"]), int(after["boundary_loops_output"])))
                lines.append(row)
                print(row, flush=True)
    before = sum(r[2] for r in rows)
    after = sum(r[3] for r in rows)
    open_cells = [f"{r[0]}@{r[1]:g}" for r in rows if r[3] > 0]
    summary = (f"\nloops in all cells: {before} without the pass, {after} with it; cells with loops left: "
               f"{len(open_cells)} of {len(rows)}" + (f" ({', '.join(open_cells)})" if open_cells else ""))
    print(summary)
    if a.out:
        with open(a.out, "w") as f:
            f.write("Command: " + " ".join([os.path.relpath(sys.argv[0], ROOT)] + sys.argv[1:]) + "\n\n")
            f.write("\n".join(lines) + "\n" + summary + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
