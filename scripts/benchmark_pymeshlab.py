"""The PyMeshLab row set of the benchmark: Sphere Packing, Robust G2S and MeshLab's Ball Pivoting
(generate_surface_reconstruction_ball_pivoting), each at its default parameters, applied to the same
cloud in one MeshSet of one Python process, so that the three timings are taken side by side.

Run by scripts/benchmark.sh --pymeshlab (in the venv of scripts/setup.sh --pymeshlab, with the
package installed by scripts/test_python.sh or `pip install .`):

    python scripts/benchmark_pymeshlab.py --clouds torus-30k,sphere-100k,hand [--repeat 3]

Clouds are NAME-SIZE of build/make_cloud (sphere, torus, patch, genus2, ...; sizes like 30k, 1m)
or the name of a PLY in --data-dir (hand, bunny_merged_normals, ...). Each filter runs --repeat
times on a fresh copy of the cloud layer; the fastest wall time counts, and the ratios are against
Ball Pivoting's fastest on the same cloud in the same run. The mesh of each row is measured by
PyMeshLab itself (get_topological_measures: non-manifold edges and vertices, boundary edges,
components) and by its vertex and face matrices (the shortest and mean of the unique edges, and their
standard deviation over the mean). Writes OUT/pymeshlab.md and
OUT/pymeshlab.jsonl, and prints the table.
"""
import argparse
import datetime
import importlib.metadata
import json
import os
import platform
import re
import subprocess
import sys
import tempfile
import time

import numpy as np
import pymeshlab

import growth_meshers

METHODS = (
    ("spherepack", "Sphere Packing", "generate_surface_reconstruction_sphere_packing"),
    ("g2s", "Robust G2S", "generate_surface_reconstruction_robust_g2s"),
    ("bpa", "Ball Pivoting", "generate_surface_reconstruction_ball_pivoting"),
)
SIZE = re.compile(r"^([a-z0-9]+)-(\d+)([km]?)$")


def cloud_path(name, tmp, make_cloud, data_dir):
    """A PLY for the cloud NAME: make_cloud's shape at a size (seed 1), or a file of data_dir."""
    m = SIZE.match(name)
    if m:
        n = int(m.group(2)) * {"": 1, "k": 1000, "m": 1000000}[m.group(3)]
        path = os.path.join(tmp, name + ".ply")
        subprocess.run([make_cloud, "--shape", m.group(1), "--points", str(n), "--seed", "1", "-o", path],
                       check=True, stdout=subprocess.DEVNULL)
        return path
    path = os.path.join(data_dir, name if name.endswith(".ply") else name + ".ply")
    if not os.path.isfile(path):
        sys.exit("benchmark_pymeshlab: no cloud %r (not NAME-SIZE, not in %s)" % (name, data_dir))
    return path


def run_filter(ms, cloud_id, filter_name):
    """Applies the filter to a copy of the cloud layer; its wall time and the output layer's id."""
    ms.set_current_mesh(cloud_id)
    layers = ms.mesh_number()
    t0 = time.perf_counter()
    getattr(ms, filter_name)()
    seconds = time.perf_counter() - t0
    # Ball Pivoting writes into the current layer; ours add a layer and make it current.
    assert ms.mesh_number() == layers + (0 if ms.current_mesh_id() == cloud_id else 1)
    return seconds, ms.current_mesh_id()


def measure(ms, mesh_id):
    ms.set_current_mesh(mesh_id)
    m = ms.current_mesh()
    topo = ms.get_topological_measures()
    row = {"vertices": m.vertex_number(), "faces": m.face_number(),
           "non_manifold_edges": topo["non_two_manifold_edges"],
           "non_manifold_vertices": topo["non_two_manifold_vertices"],
           "boundary_edges": topo["boundary_edges"], "components": topo["connected_components_number"]}
    if m.face_number() > 0:
        v = m.vertex_matrix()
        f = m.face_matrix()
        e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
        e = np.unique(np.sort(e, axis=1), axis=0)
        lengths = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
        row["edge_min"] = float(lengths.min())
        row["edge_mean"] = float(lengths.mean())
        row["edge_rel_std"] = float(lengths.std() / lengths.mean())
    return row


def bench_cloud(name, path, repeat):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(path)
    cloud_id = ms.current_mesh_id()
    points = ms.current_mesh().vertex_number()
    rows = []
    for key, label, filter_name in METHODS:
        times, status = [], "ok"
        for i in range(repeat):
            # Ball Pivoting meshes the layer it is given: each run gets a fresh copy of the cloud.
            ms.set_current_mesh(cloud_id)
            ms.generate_copy_of_current_mesh()
            copy_id = ms.current_mesh_id()
            try:
                seconds, out_id = run_filter(ms, copy_id, filter_name)
            except pymeshlab.PyMeshLabException as e:
                status = "failed: %s" % e
                break
            times.append(seconds)
            if i + 1 < repeat:  # the filters are deterministic: the last run's mesh is measured
                for layer in {out_id, copy_id}:
                    ms.set_current_mesh(layer)
                    ms.delete_current_mesh()
        row = {"cloud": name, "points": points, "method": key, "label": label, "status": status}
        if status == "ok":
            row.update({"seconds": min(times), "seconds_all": times})
            row.update(measure(ms, out_id))
        rows.append(row)
    bpa = next((r for r in rows if r["method"] == "bpa" and r["status"] == "ok"), None)
    for r in rows:
        if bpa and r.get("seconds") is not None:
            r["time_vs_bpa"] = r["seconds"] / bpa["seconds"]
    return rows


def table(rows):
    out = ["| cloud | points | method | seconds | × Ball Pivoting | faces | non-manifold edges / vertices "
           "| boundary edges | components | shortest / mean edge | edge std/mean |",
           "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        if r["status"] != "ok":
            out.append("| %s | %d | %s | %s |" % (r["cloud"], r["points"], r["label"], r["status"]))
            continue
        edges = ("%.4g / %.4g" % (r["edge_min"], r["edge_mean"])) if "edge_min" in r else "-"
        spread = ("%.3f" % r["edge_rel_std"]) if "edge_rel_std" in r else "-"
        out.append("| %s | %d | %s | %.3f | %.2f | %d | %d / %d | %d | %d | %s | %s |" % (
            r["cloud"], r["points"], r["label"], r["seconds"], r.get("time_vs_bpa", float("nan")), r["faces"],
            r["non_manifold_edges"], r["non_manifold_vertices"], r["boundary_edges"], r["components"], edges,
            spread))
    return "\n".join(out)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--clouds", default="torus-30k,sphere-100k,hand",
                    help="comma-separated NAME-SIZE (make_cloud) or PLY names of --data-dir")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--build", default=os.environ.get("GROWTH_BUILD_DIR", os.path.join(root, "build")))
    ap.add_argument("--data-dir", default=os.path.join(os.path.dirname(root), "shared", "data"))
    ap.add_argument("--out", default=os.path.join(root, "out", "benchmark"))
    args = ap.parse_args()
    make_cloud = os.path.join(args.build, "make_cloud")
    os.makedirs(args.out, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.clouds.split(","):
            path = cloud_path(name, tmp, make_cloud, args.data_dir)
            print("benchmark_pymeshlab: %s" % name, file=sys.stderr, flush=True)
            rows += bench_cloud(name, path, args.repeat)
    stamp = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    cpu = subprocess.run("lscpu | sed -n 's/^Model name: *//p' | head -1", shell=True, stdout=subprocess.PIPE,
                         universal_newlines=True).stdout.strip()
    head = "\n".join([
        "<!-- generated by scripts/benchmark.sh --pymeshlab: do not edit; rerun the command below -->",
        "# PyMeshLab %s: the three filters in one MeshSet" % importlib.metadata.version("pymeshlab"), "",
        "Command: `scripts/benchmark.sh --pymeshlab --clouds %s --repeat %d`  " % (args.clouds, args.repeat),
        "Machine: %s, `nproc` = %d.  " % (cpu or platform.processor(), os.cpu_count()),
        "Date: %s.  " % stamp,
        "PyMeshLab %s (double precision), growth_meshers %s, Python %s; the fastest of %d runs per filter." % (
            importlib.metadata.version("pymeshlab"), growth_meshers.__version__, platform.python_version(),
            args.repeat)])
    text = head + "\n\n" + table(rows) + "\n"
    with open(os.path.join(args.out, "pymeshlab.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "pymeshlab.jsonl"), "w") as f:
        for r in rows:
            r["run"] = stamp
            f.write(json.dumps(r) + "\n")
    print(text)


if __name__ == "__main__":
    main()
