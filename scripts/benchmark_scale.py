"""Ten million points for real (issue 30, item 3): a scan-like cloud from build/make_cloud (several
separate parts, Gaussian noise, stray points, some flipped normals) meshed by the Sphere Packing
filter with its automatic parameters, through both hosts, one after the other:

  meshlabserver  MeshLab 2020.09 (Debian's binary in a scratch prefix with the built plugins,
                 scripts/meshlab_env.sh, under xvfb-run and a scratch HOME) applying
                 scripts/mlx/spherepack.mlx;
  pymeshlab      PyMeshLab 2025.7 of third_party/venv, with the project's package python/growth_meshers
                 loading the built plugins (build/meshlab-2025.07d/plugins; a scratch copy of the
                 package on PYTHONPATH, nothing installed), apply_filter at the defaults.

Each run is timed by /usr/bin/time -v (wall time and peak RSS of the host process); its mesh is
measured by build/mesh_measures (shortest edge and vertex distance against d, manifoldness,
self-intersections, components, holes) and by the parts of the scan (every part holds its share of
the mesh's vertices). The guarantees checked: every edge and every vertex pair >= d (less the
rounding of the saved float coordinates and of the logged d, distance_tolerance), no non-manifold edge or vertex, no intersecting faces, every part meshed
(at least 80 % of its share of the vertices by area, and at least one component per part).
Progress: the callbacks each host shows are counted (meshlabserver prints each phase's label on
stdout at every new percentage; PyMeshLab logs "label [ p% ]" lines when the MeshSet is verbose).

Writes OUT/scale-<points>.md (the header: the command, date, machine, revision) and .json, prints
the page, exits 1 if a guarantee failed. Run by scripts/benchmark.sh --scale (which makes the
MeshLab prefix); by hand:

  python3 scripts/benchmark_scale.py --points 10m --out out/bench --build build --prefix PREFIX
"""
import argparse
import datetime
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILTER = "generate_surface_reconstruction_sphere_packing"
# Every edge and vertex pair >= d, up to the float storage of the saved mesh (each coordinate x rounded
# by at most |x| 2^-24, so a distance shrinks by at most 2 sqrt(3) M 2^-24 for coordinates up to M)
# and, for meshlabserver, the log's d printed with 6 digits (half a unit of its last digit).
PART_SHARE = 0.8        # each part holds at least this fraction of its share of the vertices by area
OUTLIERS = 0.02
NOISE_SPACINGS = 0.1
FLIPPED = 0.01


def points_arg(text):
    m = re.match(r"^(\d+(?:\.\d+)?)([km]?)$", text.lower())
    if not m:
        raise argparse.ArgumentTypeError("points like 200k, 10m or 123456")
    return int(round(float(m.group(1)) * {"": 1, "k": 1000, "m": 1000000}[m.group(2)]))


def size_name(n):
    return "%gm" % (n / 1e6) if n % 1000000 == 0 else ("%gk" % (n / 1e3) if n % 1000 == 0 else str(n))


def time_v(path):
    """Wall seconds and peak RSS (bytes) from a /usr/bin/time -v report."""
    text = open(path).read()
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", text).group(1)) * 1024
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (?:(\d+):)?(\d+):([\d.]+)", text)
    seconds = int(wall.group(1) or 0) * 3600 + int(wall.group(2)) * 60 + float(wall.group(3))
    status = re.search(r"Exit status: (\d+)", text)
    return seconds, rss, int(status.group(1)) if status else None


def machine():
    cpu = "?"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    mem = 0
    for line in open("/proc/meminfo"):
        if line.startswith("MemTotal:"):
            mem = int(line.split()[1]) * 1024
    return {"nproc": os.cpu_count(), "cpu": cpu, "ram_gb": mem / 2**30, "kernel": platform.release()}


def git_revision():
    try:
        rev = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, universal_newlines=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               stdout=subprocess.PIPE, universal_newlines=True).stdout.strip()
        return rev + (" (with uncommitted changes)" if dirty else "")
    except OSError:
        return "?"


def read_ply_vertices(path):
    """The vertex positions of a binary little-endian PLY (any vertex properties), as an N x 3 array."""
    import numpy as np
    types = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "<i2", "int16": "<i2",
             "ushort": "<u2", "uint16": "<u2", "int": "<i4", "int32": "<i4", "uint": "<u4", "uint32": "<u4",
             "float": "<f4", "float32": "<f4", "double": "<f8", "float64": "<f8"}
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline().decode("ascii", "replace").strip()
            header.append(line)
            if line == "end_header":
                break
        if "format binary_little_endian 1.0" not in header:
            raise ValueError("%s: not a binary little-endian PLY" % path)
        count, fields, in_vertex = 0, [], False
        for line in header:
            w = line.split()
            if w[:1] == ["element"]:
                in_vertex = w[1] == "vertex"
                if in_vertex:
                    count = int(w[2])
                elif count:
                    break  # the vertex element comes first in the files read here
            elif w[:1] == ["property"] and in_vertex:
                if w[1] == "list":
                    raise ValueError("%s: a list property in the vertex element" % path)
                fields.append((w[2], types[w[1]]))
        data = np.fromfile(f, dtype=np.dtype(fields), count=count)
    return np.stack([data["x"], data["y"], data["z"]], axis=1).astype(np.float64)


def part_coverage(v, parts):
    """Per part of the scan: mesh vertices (v, N x 3) in its ball (+ 5 % of its radius) over its share
    of all vertices by area (1: as dense as the whole mesh)."""
    import numpy as np
    total_area = sum(p["area"] for p in parts)
    out = []
    for p in parts:
        c = np.array(p["centre"])
        inside = int(np.count_nonzero(np.sum((v - c) ** 2, axis=1) <= (1.05 * p["radius"]) ** 2))
        expected = len(v) * p["area"] / total_area
        out.append({"shape": p["shape"], "vertices": inside, "share": inside / expected if expected else 0.0})
    return out


def make_cloud(args, path, log_path):
    n = args.points
    surface = int(round(n / (1 + OUTLIERS)))
    while surface + int(round(OUTLIERS * surface)) < n:  # llround in make_cloud: exactly n points
        surface += 1
    cmd = [os.path.join(args.build, "make_cloud"), "--shape", "scan", "--parts", str(args.parts), "--points",
           str(surface), "--seed", str(args.seed), "--gauss-spacings", str(NOISE_SPACINGS), "--outliers",
           str(OUTLIERS), "--flip-normals", str(FLIPPED), "-o", path]
    timed = ["/usr/bin/time", "-v", "-o", log_path + ".time"] + cmd
    out = subprocess.run(timed, stdout=subprocess.PIPE, universal_newlines=True, check=True).stdout
    parts = []
    for m in re.finditer(r"^part \d+: (\w+) centre (\S+) (\S+) (\S+) radius (\S+) area (\S+)$", out, re.M):
        parts.append({"shape": m.group(1), "centre": [float(m.group(i)) for i in (2, 3, 4)],
                      "radius": float(m.group(5)), "area": float(m.group(6))})
    total = int(re.search(r": (\d+) points", out).group(1))
    seconds, rss, _ = time_v(log_path + ".time")
    return {"command": " ".join(["make_cloud"] + cmd[1:-2] + ["-o", os.path.basename(path)]), "points": total,
            "parts": parts, "seconds": seconds, "peak_rss": rss,
            "sigma": float(re.search(r"gaussian sigma: (\S+)", out).group(1))}


def run_meshlabserver(args, cloud, work):
    """meshlabserver 2020.09 with scripts/mlx/spherepack.mlx (every parameter automatic)."""
    shutil.copy(os.path.join(ROOT, "scripts", "mlx", "spherepack.mlx"), os.path.join(work, "spherepack.mlx"))
    home = os.path.join(work, "home")
    os.makedirs(home, exist_ok=True)
    mesh = os.path.join(work, "mesh.ply")
    time_path = os.path.join(work, "time.txt")
    env = dict(os.environ, HOME=home)
    cmd = ["xvfb-run", "-a", "/usr/bin/time", "-v", "-o", time_path, os.path.join(args.prefix, "bin", "meshlabserver"),
           "-i", cloud, "-o", mesh, "-s", os.path.join(work, "spherepack.mlx")]
    with open(os.path.join(work, "server.log"), "w") as log:
        rc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env, cwd=work).returncode
    text = open(os.path.join(work, "server.log"), errors="replace").read()
    seconds, rss, _ = time_v(time_path)
    row = {"host": "meshlabserver 2020.09", "status": "ok" if rc == 0 and os.path.isfile(mesh) else "failed (%d)" % rc,
           "wall_seconds": seconds, "peak_rss": rss, "mesh": mesh, "log": os.path.join(work, "server.log")}
    m = re.search(r"Sphere Packing: sphere diameter d = ([0-9.eE+-]+),", text)
    row["d"] = float(m.group(1)) if m else None
    m = re.search(r"Sphere Packing: time ([0-9.]+) s", text)
    row["filter_seconds"] = float(m.group(1)) if m else None
    # Progress: meshlabserver prints the phase's label ("Sphere packing: growing", lower-case p unlike the
    # log's "Sphere Packing:") with no newline and no percentage at each new percentage.
    labels = re.findall(r"Sphere packing: [a-z ]*?(?=Sphere packing: |[^a-z ]|$)", text)
    row["progress_callbacks"] = len(labels)
    row["progress_phases"] = sorted(set(labels), key=labels.index)
    return row


CHILD = r'''
import json, os, resource, sys, time
sys.path.insert(0, sys.argv[1])
import pymeshlab
import growth_meshers
assert all(os.path.realpath(p).startswith(sys.argv[2] + os.sep) for p in growth_meshers.PLUGINS), growth_meshers.PLUGINS
ms = pymeshlab.MeshSet(verbose=True)
t0 = time.perf_counter()
ms.load_new_mesh(sys.argv[3])
t1 = time.perf_counter()
out = ms.apply_filter("%s")
t2 = time.perf_counter()
ms.save_current_mesh(sys.argv[4], binary=True, save_vertex_normal=False, save_face_quality=False,
                     save_vertex_quality=False, save_vertex_color=False, save_face_color=False)
t3 = time.perf_counter()
# The shortest edge of the layer in memory (double, as the plugin wrote it), before the file's float.
import numpy as np
m = ms.current_mesh()
v, f = m.vertex_matrix(), m.face_matrix()
edge_min = min(float(np.sqrt(((v[f[:, a]] - v[f[:, (a + 1) %% 3]]) ** 2).sum(axis=1)).min()) for a in range(3)) if len(f) else None
print("RESULT " + json.dumps({"edge_min_in_memory": edge_min,
      "outputs": {k: (v if isinstance(v, (int, float, str)) else str(v)) for k, v in out.items()},
      "load_seconds": t1 - t0, "filter_seconds": t2 - t1, "save_seconds": t3 - t2,
      "maxrss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
      "pymeshlab": pymeshlab.__version__ if hasattr(pymeshlab, "__version__") else "?"}), flush=True)
''' % FILTER


def package_dir(args, work):
    """A scratch copy of python/growth_meshers whose plugins/ are the build's (PyMeshLab 2025.7, double)."""
    plugins = os.path.join(args.build, "meshlab-2025.07d", "plugins")
    if not os.path.isfile(os.path.join(plugins, "libfilter_spherepack.so")):
        return None, plugins
    pkg = os.path.join(work, "pkg", "growth_meshers")
    shutil.rmtree(os.path.dirname(pkg), ignore_errors=True)
    os.makedirs(pkg)
    shutil.copy(os.path.join(ROOT, "python", "growth_meshers", "__init__.py"), pkg)
    os.symlink(os.path.abspath(plugins), os.path.join(pkg, "plugins"))
    return os.path.dirname(pkg), plugins


def run_pymeshlab(args, cloud, work):
    pkg, plugins = package_dir(args, work)
    row = {"host": "PyMeshLab 2025.7", "mesh": os.path.join(work, "mesh.ply"), "log": os.path.join(work, "python.log")}
    if pkg is None:
        row["status"] = "skipped: no %s (configure with -DGROWTH_MESHLAB_2025D=ON)" % plugins
        return row
    if not os.access(args.python, os.X_OK):
        row["status"] = "skipped: no %s (scripts/setup.sh --pymeshlab)" % args.python
        return row
    time_path = os.path.join(work, "time.txt")
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", HOME=os.path.join(work, "home"))
    os.makedirs(env["HOME"], exist_ok=True)
    cmd = ["/usr/bin/time", "-v", "-o", time_path, args.python, "-c", CHILD, pkg, os.path.realpath(plugins), cloud,
           row["mesh"]]
    # The log read line by line as it comes: PyMeshLab writes each progress line at once, so the
    # largest time between two of them is how long a user saw no progress.
    stamps = []
    with open(row["log"], "w") as log:
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env, cwd=work,
                                universal_newlines=True, errors="replace")
        for line in proc.stdout:
            if re.search(r"\[ *\d+% \]", line):
                stamps.append(time.perf_counter())
            log.write(line)
        rc = proc.wait()
    if len(stamps) > 1:
        row["progress_max_gap"] = max(b - a for a, b in zip(stamps, stamps[1:]))
    text = open(row["log"], errors="replace").read()
    seconds, rss, _ = time_v(time_path)
    row.update({"status": "ok" if rc == 0 else "failed (%d)" % rc, "wall_seconds": seconds, "peak_rss": rss})
    m = re.search(r"^RESULT (.*)$", text, re.M)
    if m:
        res = json.loads(m.group(1))
        row.update({"d": float(res["outputs"].get("sphere_diameter", "nan")), "filter_seconds": res["filter_seconds"],
                    "load_seconds": res["load_seconds"], "outputs": res["outputs"], "rss_in_process": res["maxrss"],
                    "edge_min_in_memory": res["edge_min_in_memory"]})
    else:
        row["status"] = "failed (%d, no result)" % rc
    # Progress: the verbose MeshSet logs each callback as "label    [ p% ]".
    row["progress_callbacks"] = len(re.findall(r"\[ *\d+% \]", text))
    lines = re.findall(r"(Sphere packing: [a-z ]*?) *\[ *\d+% \]", text)
    row["progress_phases"] = sorted(set(lines), key=lines.index)
    return row


def distance_tolerance(vertices, d, d_digits, bits=24):
    import math
    import numpy as np
    biggest = float(np.abs(vertices).max()) if len(vertices) else 0.0
    tol = 2 * math.sqrt(3) * biggest * 2.0 ** -bits
    if d_digits:
        tol += 0.5 * 10.0 ** (math.floor(math.log10(d)) - (d_digits - 1))
    return tol


def measure(args, row, parts):
    mm = subprocess.run([os.path.join(args.build, "mesh_measures"), row["mesh"]], stdout=subprocess.PIPE,
                        universal_newlines=True)
    if mm.returncode != 0:
        row["checks"] = {"mesh_measures ran": False}
        return
    m = json.loads(mm.stdout)
    d = row.get("d") or float("nan")
    vertices = read_ply_vertices(row["mesh"])
    coverage = part_coverage(vertices, parts)
    # The d of meshlabserver's log has 6 significant digits (%g); PyMeshLab's output is the double.
    tol = distance_tolerance(vertices, d, 6 if row["host"].startswith("meshlabserver") else 0)
    row["distance_tolerance"] = tol
    row["measures"] = {k: m[k] for k in ("vertices", "faces", "edge_min", "edge_mean", "min_vertex_distance",
                                         "non_manifold_edges", "non_manifold_vertices", "self_intersecting_pairs",
                                         "components", "boundary_loops", "inconsistent_edges", "quality_mean",
                                         "measure_seconds")}
    row["parts"] = coverage
    row["checks"] = {
        "every edge >= d": m["edge_min"] >= d - tol,
        "every vertex pair >= d": m["min_vertex_distance"] >= d - tol,
        "manifold": m["non_manifold_edges"] == 0 and m["non_manifold_vertices"] == 0,
        "no intersecting faces": m["self_intersecting_pairs"] == 0,
        "every part meshed": all(c["share"] >= PART_SHARE for c in coverage) and m["components"] >= len(parts),
    }
    if row.get("edge_min_in_memory") is not None:
        # PyMeshLab's double layer: only the rounding of the coordinates to doubles (the engine works
        # on coordinates about its own origin and moves the vertices back), one ulp each.
        row["checks"]["every edge >= d in memory (double)"] = \
            row["edge_min_in_memory"] >= d - distance_tolerance(vertices, d, 0, bits=52)


def gb(x):
    return "%.2f GB" % (x / 1e9) if x else "-"


def page(args, command, stamp, mach, cloud, rows):
    lines = ["# Sphere Packing at %s points: meshlabserver and PyMeshLab" % "{:,}".format(cloud["points"]), "",
             "- Command: `%s`" % command,
             "- Date: %s; revision %s" % (stamp, git_revision()),
             "- Machine: %d cores (`nproc`), %s, %.1f GB RAM, Linux %s; load average %.2f at the end"
             % (mach["nproc"], mach["cpu"], mach["ram_gb"], mach["kernel"], os.getloadavg()[0]),
             "- Cloud: `%s`: %s points, %d parts (%s), Gaussian sigma %.4g (%.2g of the spacing), %g %% stray "
             "points, %g %% flipped normals; made in %.1f s, peak RSS %s" % (
                 cloud["command"], "{:,}".format(cloud["points"]), len(cloud["parts"]),
                 ", ".join(p["shape"] for p in cloud["parts"]), cloud["sigma"], NOISE_SPACINGS, 100 * OUTLIERS,
                 100 * FLIPPED, cloud["seconds"], gb(cloud["peak_rss"])),
             "- Filter: Surface Reconstruction: Sphere Packing, every parameter automatic "
             "(scripts/mlx/spherepack.mlx; `ms.apply_filter('%s')`)" % FILTER, "",
             "| host | status | wall | filter | peak RSS | bytes / point | d | vertices | faces | holes "
             "| shortest edge / d | closest vertices / d | non-manifold e / v | intersecting pairs | components "
             "| parts' vertex share (min) | progress callbacks seen |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        if "measures" not in r:
            lines.append("| %s | %s |" % (r["host"], r["status"]) + " |" * 15)
            continue
        m, d = r["measures"], r["d"]
        lines.append("| %s | %s | %.1f s | %s | %s | %.0f | %.6g | %s | %s | %d | %.7f | %.7f | %d / %d | %d | %d | %.3f | %d |" % (
            r["host"], r["status"], r["wall_seconds"],
            "%.1f s" % r["filter_seconds"] if r.get("filter_seconds") is not None else "-", gb(r["peak_rss"]),
            r["peak_rss"] / cloud["points"], d, "{:,}".format(m["vertices"]), "{:,}".format(m["faces"]),
            m["boundary_loops"], m["edge_min"] / d, m["min_vertex_distance"] / d, m["non_manifold_edges"],
            m["non_manifold_vertices"], m["self_intersecting_pairs"], m["components"],
            min(c["share"] for c in r["parts"]), r.get("progress_callbacks", 0)))
    lines += ["", "Guarantees (every edge and vertex pair >= d, less the float storage's rounding and for "
              "meshlabserver the log's 6 digits of d: %s; manifold; no intersecting faces; every part holding "
              ">= %g of its share of the vertices by area, and at least one component per part):" % (
                  ", ".join("%s %.2g d" % (r["host"], r["distance_tolerance"] / r["d"]) for r in rows
                            if "distance_tolerance" in r), PART_SHARE), ""]
    for r in rows:
        if "checks" in r:
            bad = [k for k, ok in r["checks"].items() if not ok]
            lines.append("- %s: %s" % (r["host"], "all hold" if not bad else "FAILED: " + ", ".join(bad)))
        else:
            lines.append("- %s: %s" % (r["host"], r["status"]))
    for r in rows:
        if r.get("edge_min_in_memory") is not None:
            lines.append("- %s, in memory before saving (double): shortest edge %.15g = (1 %+.1e) d" % (
                r["host"], r["edge_min_in_memory"], r["edge_min_in_memory"] / r["d"] - 1))
    lines += ["", "Vertices per part (share of its area's share): " + "; ".join(
        "%s: %s" % (r["host"], ", ".join("%s %s (%.3f)" % (c["shape"], "{:,}".format(c["vertices"]), c["share"])
                                         for c in r["parts"])) for r in rows if "parts" in r), ""]
    lines += ["Progress seen: " + "; ".join("%s: %d callbacks%s (%s)" % (
        r["host"], r.get("progress_callbacks", 0),
        ", at most %.1f s apart" % r["progress_max_gap"] if "progress_max_gap" in r else "",
        ", ".join(r.get("progress_phases", [])) or "none") for r in rows) + ". meshlabserver prints each "
              "phase's label with no percentage and no newline, so stdout's buffer shows them in bursts; "
              "PyMeshLab logs one line per percent when the MeshSet is verbose.", ""]
    lines += ["Wall and peak RSS: /usr/bin/time -v of the host process (meshlabserver: inside xvfb-run; PyMeshLab: "
              "the Python process), loading the cloud and saving the mesh included. Filter: the filter's own "
              "time (its log; PyMeshLab: apply_filter's wall time).", ""]
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=points_arg, default=points_arg("10m"), help="e.g. 200k, 10m (outliers included)")
    ap.add_argument("--parts", type=int, default=6)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--hosts", default="meshlabserver,pymeshlab")
    ap.add_argument("--build", default=os.environ.get("GROWTH_BUILD_DIR", os.path.join(ROOT, "build")))
    ap.add_argument("--prefix", required=True, help="the scratch MeshLab prefix (scripts/meshlab_env.sh)")
    ap.add_argument("--python", default=os.path.join(ROOT, "third_party", "venv", "bin", "python"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    ap.add_argument("--command", default=None, help="the command to record (default: this one)")
    ap.add_argument("--keep", action="store_true", help="keep the cloud and the meshes")
    args = ap.parse_args()
    args.build = os.path.abspath(args.build)
    args.prefix = os.path.abspath(args.prefix)
    command = args.command or "python3 scripts/benchmark_scale.py " + " ".join(sys.argv[1:])
    name = "scale-%s" % size_name(args.points)
    work = os.path.join(os.path.abspath(args.out), name)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    cloud_path = os.path.join(work, "cloud.ply")
    print("benchmark_scale: making the cloud", file=sys.stderr, flush=True)
    cloud = make_cloud(args, cloud_path, os.path.join(work, "make_cloud"))
    rows = []
    for host in args.hosts.split(","):
        hw = os.path.join(work, host)
        os.makedirs(hw, exist_ok=True)
        print("benchmark_scale: %s" % host, file=sys.stderr, flush=True)
        row = run_meshlabserver(args, cloud_path, hw) if host == "meshlabserver" else run_pymeshlab(args, cloud_path, hw)
        if row["status"] == "ok":
            measure(args, row, cloud["parts"])
        rows.append(row)
    text = page(args, command, stamp, machine(), cloud, rows)
    with open(os.path.join(os.path.abspath(args.out), name + ".md"), "w") as f:
        f.write(text)
    with open(os.path.join(os.path.abspath(args.out), name + ".json"), "w") as f:
        json.dump({"command": command, "date": stamp, "machine": machine(), "cloud": cloud, "rows": rows}, f, indent=1)
    if not args.keep:
        for path in [cloud_path] + [r["mesh"] for r in rows]:
            if os.path.exists(path):
                os.remove(path)
    print(text)
    ok = all(r["status"] == "ok" or r["status"].startswith("skipped") for r in rows) and \
        all(all(r["checks"].values()) for r in rows if "checks" in r)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
