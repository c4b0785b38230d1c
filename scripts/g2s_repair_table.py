#!/usr/bin/env python3
"""Robust G2S's repairs (filter_g2s/engine/g2s_repair.cpp, docs/design/g2s-hole-pass.md) against a
build without them and CGAL's advancing front: for each cloud, the mesh of BEFORE (a g2s_run without
the repairs), of AFTER with --holes 0 (the intersection removal only) and with its defaults, and of
afsr_run, all measured by mesh_measures; prints a Markdown table.

  scripts/g2s_repair_table.py --before OLD_BUILD/g2s_run --build build --out out/repair CLOUD.ply...
"""
import argparse, json, os, subprocess


def run_g2s(exe, cloud, extra, mesh):
    r = subprocess.run([exe, cloud] + extra + ["-o", mesh], stdout=subprocess.PIPE, universal_newlines=True, check=True)
    return dict(l.split(": ", 1) for l in r.stdout.splitlines() if ": " in l)


def measure(tool, mesh, cloud):
    r = subprocess.run([tool, mesh, "--cloud", cloud], stdout=subprocess.PIPE, universal_newlines=True, check=True)
    return json.loads(r.stdout)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--before", required=True, help="g2s_run of the build without the repairs")
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="out/repair")
    ap.add_argument("clouds", nargs="+")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    tool = os.path.join(a.build, "mesh_measures")
    g2s, afsr = os.path.join(a.build, "g2s_run"), os.path.join(a.build, "afsr_run")
    print("| cloud | holes: before / removal only / with hole pass / CGAL | boundary edges: before / with hole pass / CGAL "
          "| intersecting pairs: before / now / CGAL | non-manifold V, E now | μd %: before / now / CGAL "
          "| faces removed (intersecting) | holes closed (faces added, replaced) | G2S holes ≤ CGAL's |")
    print("|---|---|---|---|---|---|---|---|---|")
    for cloud in a.clouds:
        name = os.path.splitext(os.path.basename(cloud))[0]
        m = {}
        for label, exe, extra in (("before", a.before, []), ("off", g2s, ["--holes", "0"]), ("now", g2s, [])):
            mesh = os.path.join(a.out, "%s-%s.ply" % (name, label))
            st = run_g2s(exe, cloud, extra, mesh)
            m[label] = (st, measure(tool, mesh, cloud))
        mesh = os.path.join(a.out, "%s-cgal.ply" % name)
        subprocess.run([afsr, cloud, "-o", mesh], stdout=subprocess.DEVNULL, check=True)
        c = measure(tool, mesh, cloud)
        b, o, (st, n) = m["before"][1], m["off"][1], m["now"]
        print("| %s | %d / %d / %d / %d | %d / %d / %d | %d / %d / %d | %d, %d | %.2f / %.2f / %.2f | %s | %s (%s, %s) | %s |" % (
            name, b["boundary_loops"], o["boundary_loops"], n["boundary_loops"], c["boundary_loops"],
            b["boundary_edges"], n["boundary_edges"], c["boundary_edges"],
            b["self_intersecting_pairs"], n["self_intersecting_pairs"], c["self_intersecting_pairs"],
            n["non_manifold_vertices"], n["non_manifold_edges"],
            b["mu_d_percent"] or 0, n["mu_d_percent"] or 0, c["mu_d_percent"] or 0,
            st["self_intersection_faces_removed"], st["holes_closed"], st["hole_faces_added"], st["hole_faces_replaced"],
            "yes" if n["boundary_loops"] <= c["boundary_loops"] else "**no**"), flush=True)


if __name__ == "__main__":
    main()
