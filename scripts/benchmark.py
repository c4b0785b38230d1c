#!/usr/bin/python3
"""The comparison benchmark: our two meshers against MeshLab's Ball Pivoting, in the same run.

Called by scripts/benchmark.sh (which builds the project and makes the scratch MeshLab prefix); see
there for the usage. For every cloud and method it runs meshlabserver once (plus one load+save-only
run of the cloud, the baseline), measures the mesh with build/mesh_measures, and writes

  OUT/results.jsonl                 one JSON row per (cloud, method), merged across invocations
  OUT/results.md                    the Markdown tables (one per cloud) and the plots
  OUT/plots/<cloud>_histograms.png  angles, edge lengths, Q_t per method (sphere-packing fig. 12)
  OUT/plots/scaling.png             time against points, log-log, fitted slope per method
  OUT/runs/<cloud>/<method>/        the .mlx, meshlabserver's log, /usr/bin/time's report,
                                    the mesh, its measures (JSON) and histograms (CSV)
  OUT/clouds/                       the generated clouds, horse's vertices, and the "-ml" clouds

Methods: Ball Pivoting with auto radius ("bpa"), with r = 3 × the mean spacing ("bpa3"), bpa's mesh
remeshed ("bpa_re"); the sphere packer at its default d ("spherepack") and at d = 2.5 × the mean
spacing ("spherepack25"); Robust G2S ("g2s"); and, not through meshlabserver, CGAL's Advancing Front
Surface Reconstruction with its defaults ("cgal-afsr", build/afsr_run, built when CGAL is found). Clouds: generated (sphere-10k, torus-1M, ...), the
scans of the data folder (bunny, hand, horse), generated ones with Gaussian noise or outliers
(sphere-100k-gauss25, torus-50k-out10; the groups "noisy" and "noisy-<size>"), .ply paths, and any of those but a path with "-ml"
appended (hand-ml, sphere-10k-ml): the same points with MeshLab's own normals (Compute normals for
point sets, K = 10, no smoothing, no flip), made by the scratch meshlabserver into OUT/clouds/.

Time: on clouds up to --inproc-max-points (100k by default), every filter, ours and MeshLab's, is
timed in process by build/plugin_time: the plugin loaded and applied as meshlabserver does, one steady
clock around applyFilter, the fastest of up to 5 repeats. Above that, our filters report their own
time in the log ("... time X s"), and MeshLab's are timed as the wall clock of the run minus the wall
clock of the load+save-only run of the same cloud (0.01 s resolution: small beside their times there).
Memory: peak resident set size of meshlabserver (/usr/bin/time -v) minus that of the
load+save-only run, per input point: the filter's extra peak. Also minus that of a run applying a
filter that does nothing (MeshLab's "Select None"): MeshLab's own cost of applying any filter, about
5 MB, which no filter can avoid and which dominates on small clouds; and, per shape, the fitted
per-point slope of the extra peak over the generated clouds' sizes.
Needs numpy and matplotlib from Debian (/usr/bin/python3), installed by scripts/setup.sh.
"""
import argparse
import datetime
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

METHODS = {
    # key: (label in the tables, short label in the plots)
    "bpa": ("Ball Pivoting (auto radius)", "BPA"),
    "bpa3": ("Ball Pivoting (r = 3 × spacing)", "BPA 3s"),
    "bpa_re": ("Ball Pivoting + remeshing (Re)", "BPA (Re)"),
    "spherepack": ("Sphere Packing (ours)", "Sphere Packing"),
    "spherepack25": ("Sphere Packing (ours, d = 2.5 × spacing)", "Sphere Packing d 2.5s"),
    "g2s": ("Robust G2S (ours)", "Robust G2S"),
    "cgal-afsr": ("CGAL Advancing Front (defaults)", "CGAL AFSR"),
}
# The peer that is not a MeshLab filter: CGAL's Advancing Front Surface Reconstruction with its
# defaults (radius_ratio_bound 5, beta 0.52), run by build/afsr_run (tools/cgal/afsr_run.cpp, built
# when CGAL is found). Timed by the tool itself: the reconstruction call alone (Delaunay
# triangulation included, reading and writing not), the fastest of the row's repeats.
AFSR = "cgal-afsr"
NOT_MESHLAB = (AFSR,)
# Run order within a cloud: the sphere packer first, its d is the remeshing target of "bpa_re".
RUN_ORDER = ["spherepack", "spherepack25", "g2s", "bpa", "bpa3", "bpa_re", AFSR]
TABLE_ORDER = ["bpa", "bpa3", "bpa_re", AFSR, "spherepack", "spherepack25", "g2s"]
OURS = ("spherepack", "spherepack25", "g2s")
SPHERE_PACKERS = ("spherepack", "spherepack25")
SPHEREPACK25_SPACINGS = 2.5      # "spherepack25": sphereDiameter = 2.5 × the cloud's mean spacing
REFERENCE = "bpa"
SHAPES = ["sphere", "torus", "patch"]
DATA = {
    "bunny": "bunny_merged_normals.ply",
    "hand": "hand.ply",
    "horse": "horse_mesh.ply",   # its vertices (with their normals) as a clean cloud
}
# "<cloud>-ml": the same points with their normals replaced by MeshLab's own estimate (Compute normals
# for point sets with these parameters), made through the scratch meshlabserver into OUT/clouds/.
ML_NORMALS_SUFFIX = "-ml"
ML_NORMALS_PARAMS = {"K": 10, "smoothIter": 0, "flipFlag": "false", "viewPos": (0, 0, 0)}
ML_NORMALS_TEXT = "MeshLab's Compute normals for point sets (K = 10, smoothIter 0, flipFlag false, viewPos 0,0,0)"
DATA_CLOUDS = [n for d in DATA for n in (d, d + ML_NORMALS_SUFFIX)]
QUICK_DATA_CLOUDS = ["hand", "hand" + ML_NORMALS_SUFFIX]
# Perturbed generated clouds: "<shape>-<size>-gauss<P>" has isotropic Gaussian noise of standard
# deviation P % of the clean cloud's mean spacing (Robust G2S sec. 5.2), "<shape>-<size>-out<P>" P %
# outliers on top of the surface points, uniform in the enlarged box (make_cloud --outliers).
# The group "noisy" (or "noisy-<size>", default 100k) is every one of NOISE_LEVELS on every shape of
# --shapes; "scans" is the clouds of the data folder with their own normals.
NOISE_LEVELS = ["gauss10", "gauss25", "gauss50", "out5", "out10", "out20"]
NOISY_GROUP_SIZE = 100000
FULL_SIZES = [10000, 30000, 100000, 300000, 1000000]
QUICK_SIZES = [10000, 30000]
EDGE_HISTOGRAM_SPACINGS = 6.0    # edge histograms over [0, max(6 × mean spacing, 1.5 × d)], same for all
EDGE_HISTOGRAM_D = 1.5           # methods of a cloud (d: the sphere packer's, whose edges are >= d)


def edge_histogram_max(spacing, d):
    return max(EDGE_HISTOGRAM_SPACINGS * spacing, EDGE_HISTOGRAM_D * (d or 0.0))


def measure_mesh(ctx, mesh, cloud_path, work, edge_max):
    """Runs build/mesh_measures on a saved mesh (measures.json and the hist_*.csv histograms into
    `work`); returns the measures, or None when the tool failed."""
    mm = subprocess.run([ctx.tool("mesh_measures"), mesh, "--cloud", cloud_path, "--histograms",
                         os.path.join(work, "hist"), "--edge-max", "%.9g" % edge_max],
                        stdout=subprocess.PIPE, universal_newlines=True)
    if mm.returncode != 0:
        return None
    with open(os.path.join(work, "measures.json"), "w") as f:
        f.write(mm.stdout)
    return json.loads(mm.stdout)


def parse_size(text):
    t = text.strip().lower()
    mult = 1
    if t.endswith("k"):
        mult, t = 1000, t[:-1]
    elif t.endswith("m"):
        mult, t = 1000000, t[:-1]
    return int(float(t) * mult)


def size_label(n):
    if n >= 1000000 and n % 1000000 == 0:
        return "%dM" % (n // 1000000)
    if n >= 1000 and n % 1000 == 0:
        return "%dk" % (n // 1000)
    return str(n)


def log(msg):
    print("[benchmark %s] %s" % (time.strftime("%H:%M:%S"), msg), flush=True)


# --- Clouds ---------------------------------------------------------------------------------

def ply_vertices_only(src, dst):
    """Writes the vertex element of a binary little-endian PLY (whose first element is the vertex
    element) as a new PLY without faces."""
    with open(src, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in header:
        raise RuntimeError("%s: only binary little-endian PLY is supported here" % src)
    sizes = {"char": 1, "uchar": 1, "int8": 1, "uint8": 1, "short": 2, "ushort": 2, "int16": 2,
             "uint16": 2, "int": 4, "uint": 4, "int32": 4, "uint32": 4, "float": 4, "float32": 4,
             "double": 8, "float64": 8}
    out, count, stride, in_vertex = [], 0, 0, False
    for line in header:
        w = line.split()
        if w and w[0] == "element":
            if in_vertex:
                break
            in_vertex = w[1] == "vertex"
            if not in_vertex:
                raise RuntimeError("%s: the vertex element must come first" % src)
            count = int(w[2])
        elif w and w[0] == "property" and in_vertex:
            if w[1] == "list":
                raise RuntimeError("%s: list property in the vertex element" % src)
            stride += sizes[w[1]]
        if not (w and w[0] == "end_header"):
            out.append(line)
    body = data[end:end + count * stride]
    with open(dst, "wb") as f:
        f.write(("\n".join(out + ["end_header"]) + "\n").encode("ascii"))
        f.write(body)


def normals_mlx():
    """The .mlx of MeshLab's "Compute normals for point sets" with ML_NORMALS_PARAMS."""
    p = ML_NORMALS_PARAMS
    return mlx(['<filter name="Compute normals for point sets">\n'
                '  <Param name="K" type="RichInt" value="%d"/>\n'
                '  <Param name="smoothIter" type="RichInt" value="%d"/>\n'
                '  <Param name="flipFlag" type="RichBool" value="%s"/>\n'
                '  <Param name="viewPos" type="RichPoint3f" x="%g" y="%g" z="%g"/>\n'
                ' </filter>' % ((p["K"], p["smoothIter"], p["flipFlag"]) + tuple(p["viewPos"]))])


def meshlab_normals(ctx, src, dst, name):
    """Writes `src` with its normals replaced by MeshLab's estimate to `dst` (vertices and normals
    only), through the scratch meshlabserver; the script and its log stay in OUT/runs/<name>/_normals."""
    work = os.path.join(ctx.out, "runs", name, "_normals")
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(work, "normals.mlx"), "w") as f:
        f.write(normals_mlx())
    if not os.path.exists(os.path.join(ctx.prefix, "bin", "meshlabserver")):
        raise SystemExit("%s: %s is missing and there is no MeshLab prefix to make it (run without "
                         "--report-only)" % (name, dst))
    partial = dst[:-len(".ply")] + ".partial.ply"
    r = run_meshlabserver(ctx, work, ["-i", src, "-o", partial, "-m", "vn", "-s", "normals.mlx"], ctx.timeout)
    if r["rc"] != 0 or not os.path.exists(partial):
        raise SystemExit("%s: MeshLab's normal estimation failed (%s); see %s"
                         % (name, failure_reason(r["log"]), work))
    os.replace(partial, dst)
    log("%s: normals by %s, %.1f s (meshlabserver wall clock)" % (name, ML_NORMALS_TEXT, r["wall"] or 0))


def prepare_cloud(spec, ctx):
    """Returns a dict with name, path, kind, shape, points, spacing, diagonal, normals."""
    clouds_dir = os.path.join(ctx.out, "clouds")
    os.makedirs(clouds_dir, exist_ok=True)
    shape, normals, perturbation = None, "own", None
    if spec.endswith(ML_NORMALS_SUFFIX) and not spec.endswith(".ply"):
        base = prepare_cloud(spec[:-len(ML_NORMALS_SUFFIX)], ctx)
        if base is None:
            return None
        # No shape: a generated cloud with MeshLab's normals stays out of the per-shape fits.
        name, kind, normals = base["name"] + ML_NORMALS_SUFFIX, base["kind"], "meshlab"
        path = os.path.join(clouds_dir, name + ".ply")
        if not os.path.exists(path):
            meshlab_normals(ctx, base["path"], path, name)
    elif spec in DATA:
        src = os.path.join(ctx.data_dir, DATA[spec])
        if not os.path.exists(src):
            return None
        name, kind = spec, "data"
        if spec == "horse":
            path = os.path.join(clouds_dir, "horse.ply")
            if not os.path.exists(path):
                ply_vertices_only(src, path)
        else:
            path = src
    elif spec.endswith(".ply"):
        path, kind = os.path.abspath(spec), "file"
        name = os.path.splitext(os.path.basename(spec))[0]
    else:
        m = re.match(r"^(sphere|torus|patch)-([0-9.]+[kKmM]?)(?:-(gauss|out)([0-9.]+))?$", spec)
        if not m:
            raise SystemExit("unknown cloud '%s' (use sphere-10k, torus-1M, patch-30000, %s, a .ply path, any "
                             "of these but a path with %s for MeshLab's normals, a generated one with -gauss<P> "
                             "or -out<P> appended (sphere-100k-gauss25: noise of 25 %% of the spacing, "
                             "sphere-100k-out10: 10 %% outliers), or the groups noisy[-<size>] and scans)"
                             % (spec, ", ".join(DATA), ML_NORMALS_SUFFIX))
        shape, n = m.group(1), parse_size(m.group(2))
        name, kind = "%s-%s" % (shape, size_label(n)), "generated"
        extra = []
        if m.group(3):
            # Perturbed: no shape, so that the per-shape fits and plots keep to the clean clouds.
            clean = prepare_cloud(name, ctx)
            level = float(m.group(4))
            name = "%s-%s%s" % (name, m.group(3), m.group(4))
            shape, perturbation = None, m.group(3) + m.group(4)
            if m.group(3) == "gauss":
                extra = ["--gauss", "%.9g" % (level / 100.0 * clean["spacing"])]
            else:
                extra = ["--outliers", "%.9g" % (level / 100.0)]
        path = os.path.join(clouds_dir, name + ".ply")
        if not os.path.exists(path):
            subprocess.run([ctx.tool("make_cloud"), "--shape", m.group(1), "--points", str(n), "--seed", "1"]
                           + extra + ["-o", path], check=True, stdout=subprocess.DEVNULL)
    # Spacing and size from mesh_measures run on the cloud itself (no faces: distances are null).
    r = subprocess.run([ctx.tool("mesh_measures"), path, "--cloud", path, "--no-min-vertex-distance"],
                       check=True, stdout=subprocess.PIPE, universal_newlines=True)
    j = json.loads(r.stdout)
    return {"name": name, "path": path, "kind": kind, "shape": shape, "points": j["cloud_points"],
            "spacing": j["cloud_spacing"], "diagonal": j["box_diagonal"], "normals": normals,
            "perturbation": perturbation}


# --- Filter scripts -------------------------------------------------------------------------

def mlx_filters(path):
    """The <filter>…</filter> blocks of an .mlx file."""
    text = open(path).read()
    return re.findall(r"<filter\b[^>]*/>|<filter\b[^>]*[^/]>.*?</filter>", text, flags=re.S)


def set_param(filter_xml, name, value):
    pat = re.compile(r'(<Param\b[^>]*\bname="%s"[^>]*>)' % re.escape(name))
    m = pat.search(filter_xml)
    if not m:
        raise SystemExit("parameter %s not found in the filter script" % name)
    tag = re.sub(r'\bvalue="[^"]*"', 'value="%s"' % value, m.group(1))
    return filter_xml[:m.start()] + tag + filter_xml[m.end():]


def set_abs_perc(filter_xml, name, value, diagonal):
    """A RichAbsPerc parameter with an absolute value (and a max that admits it)."""
    x = set_param(filter_xml, name, "%.9g" % value)
    pat = re.compile(r'(<Param\b[^>]*\bname="%s"[^>]*>)' % re.escape(name))
    m = pat.search(x)
    tag = re.sub(r'\bmax="[^"]*"', 'max="%.9g"' % max(diagonal, value), m.group(1))
    return x[:m.start()] + tag + x[m.end():]


def mlx(filters):
    return "<!DOCTYPE FilterScript>\n<FilterScript>\n " + "\n ".join(filters) + "\n</FilterScript>\n"


def remesh_filter(target, diagonal):
    """MeshLab's Isotropic Explicit Remeshing as in the paper's "(Re)" rows: 3 iterations, target
    edge length d in absolute units, MeshLab's defaults otherwise (surface distance check on with
    1 % of the diagonal, crease angle 30°, all steps on)."""
    return ('<filter name="Remeshing: Isotropic Explicit Remeshing">\n'
            '  <Param name="Iterations" type="RichInt" value="3"/>\n'
            '  <Param name="Adaptive" type="RichBool" value="false"/>\n'
            '  <Param name="SelectedOnly" type="RichBool" value="false"/>\n'
            '  <Param name="TargetLen" type="RichAbsPerc" value="%.9g" min="0" max="%.9g"/>\n'
            '  <Param name="FeatureDeg" type="RichFloat" value="30"/>\n'
            '  <Param name="CheckSurfDist" type="RichBool" value="true"/>\n'
            '  <Param name="MaxSurfDist" type="RichAbsPerc" value="%.9g" min="0" max="%.9g"/>\n'
            '  <Param name="SplitFlag" type="RichBool" value="true"/>\n'
            '  <Param name="CollapseFlag" type="RichBool" value="true"/>\n'
            '  <Param name="SwapFlag" type="RichBool" value="true"/>\n'
            '  <Param name="SmoothFlag" type="RichBool" value="true"/>\n'
            '  <Param name="ReprojectFlag" type="RichBool" value="true"/>\n'
            ' </filter>') % (target, max(diagonal, target), 0.01 * diagonal, diagonal)


def method_script(method, cloud, ctx, d_info):
    mlx_dir = os.path.join(ROOT, "scripts", "mlx")
    diag = cloud["diagonal"]
    if method in ("bpa", "bpa3", "bpa_re"):
        (f,) = mlx_filters(os.path.join(mlx_dir, "ball_pivoting.mlx"))
        info = {}
        if method == "bpa3":
            r = 3.0 * cloud["spacing"]
            f = set_abs_perc(f, "BallRadius", r, diag)
            info["ball_radius"] = r
        filters = [f]
        if method == "bpa_re":
            filters.append(remesh_filter(d_info["d"], diag))
            info["remesh_target"] = d_info["d"]
            info["remesh_target_source"] = d_info["source"]
        return mlx(filters), info
    template = {"spherepack": "spherepack.mlx", "spherepack25": "spherepack.mlx", "g2s": "g2s.mlx"}[method]
    filters = mlx_filters(os.path.join(mlx_dir, template))
    info = {}
    if method == "spherepack25":
        d = SPHEREPACK25_SPACINGS * cloud["spacing"]
        filters = [set_abs_perc(f, "sphereDiameter", d, diag) for f in filters]
        info["sphere_diameter_set"] = d
    # --param spherepack:... applies to both sphere packer methods (spherepack25:... to that one only).
    params = ctx.params.get(method, [])
    if method == "spherepack25":
        params = ctx.params.get("spherepack", []) + params
    for key, value in params:
        filters = [set_param(f, key, value) for f in filters]
    info["params"] = dict(params)
    return mlx(filters), info


# --- Running meshlabserver ------------------------------------------------------------------

def parse_time_report(path):
    """Wall clock (s), max RSS (kB) and exit status from /usr/bin/time -v."""
    wall = rss = status = None
    if os.path.exists(path):
        for line in open(path, errors="replace"):
            line = line.strip()
            if line.startswith("Elapsed (wall clock) time"):
                t = line.rsplit(" ", 1)[-1].split(":")
                wall = sum(float(x) * 60 ** i for i, x in enumerate(reversed(t)))
            elif line.startswith("Maximum resident set size"):
                rss = int(line.rsplit(" ", 1)[-1])
            elif line.startswith("Exit status"):
                status = int(line.rsplit(" ", 1)[-1])
    return wall, rss, status


def run_meshlabserver(ctx, workdir, args, timeout):
    """Like run_meshlabserver of scripts/meshlab_env.sh (the copy of meshlabserver in the scratch
    prefix, under xvfb-run), with /usr/bin/time -v inside xvfb-run so that the wall clock and the
    peak memory are meshlabserver's own, not those of the X server's start-up."""
    os.makedirs(workdir, exist_ok=True)
    tfile = os.path.join(workdir, "time.txt")
    logfile = os.path.join(workdir, "meshlabserver.log")
    if os.path.exists(tfile):
        os.remove(tfile)
    cmd = ["xvfb-run", "-a", "/usr/bin/time", "-v", "-o", tfile,
           os.path.join(ctx.prefix, "bin", "meshlabserver")] + args
    timed_out = False
    with open(logfile, "w") as logf:
        proc = subprocess.Popen(cmd, cwd=workdir, stdout=logf, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            os.killpg(proc.pid, 15)
            proc.wait()
    wall, rss, status = parse_time_report(tfile)
    return {"rc": proc.returncode if status is None else status, "wall": wall, "rss_kb": rss,
            "timed_out": timed_out, "log": open(logfile, errors="replace").read()}


def failure_reason(log_text):
    """The most telling line of a failed run's log."""
    lines = [l.strip() for l in log_text.splitlines() if l.strip()]
    for l in lines:
        if l.startswith("LOG: 1 "):   # warnings, where our filters put their errors
            return l[len("LOG: 1 "):]
    for l in lines:
        if "Problem with filter" in l or "not implemented" in l.lower() or "error" in l.lower():
            return l
    return lines[-1] if lines else "no output"


# Filter → the MeshLab plugin that holds it (for in-process timing with build/plugin_time).
PLUGIN_OF_FILTER = {
    "Surface Reconstruction: Ball Pivoting": "libfilter_clean.so",
    "Remeshing: Isotropic Explicit Remeshing": "libfilter_meshing.so",
    "Surface Reconstruction: Sphere Packing": "libfilter_spherepack.so",
    "Surface Reconstruction: Robust G2S": "libfilter_g2s.so",
}
INPROC_REPEAT = 5          # in-process timing: at most this many repeats (fastest kept) ...
INPROC_MIN_SECONDS = 3.0   # ... stopping once this much filter time was spent ...
INPROC_MIN_REPEATS = 1     # ... but not before this many (plugin_time --min-repeats; the published
                           # rows were timed with 1)


def inproc_time(ctx, script_path, input_path, work):
    """Times the one filter of `script_path` on `input_path` in process with build/plugin_time (the
    plugin loaded from the scratch prefix, as meshlabserver loads it; one steady clock around
    applyFilter; fastest of up to INPROC_REPEAT repeats). Returns (seconds, repeats) or None."""
    filters = mlx_filters(script_path)
    if len(filters) != 1:
        return None
    name = re.search(r'name="([^"]*)"', filters[0]).group(1)
    so = PLUGIN_OF_FILTER.get(name)
    tool = ctx.tool("plugin_time")
    if so is None or not os.path.exists(tool):
        return None
    plugin = os.path.join(ctx.prefix, "lib", "x86_64-linux-gnu", "meshlab", "plugins", so)
    proc = subprocess.run([tool, plugin, script_path, input_path, "--repeat", str(INPROC_REPEAT),
                           "--min-seconds", str(INPROC_MIN_SECONDS), "--min-repeats", str(INPROC_MIN_REPEATS)], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True, timeout=ctx.timeout)
    with open(os.path.join(work, "plugin_time.txt"), "w") as f:
        f.write(proc.stdout + proc.stderr[-4000:])
    if proc.returncode != 0:
        log("  plugin_time failed (%d): %s" % (proc.returncode, proc.stderr.strip()[-300:]))
        return None
    m = re.search(r"^seconds: ([0-9.eE+-]+)$", proc.stdout, flags=re.M)
    reps = re.search(r"^repeats:(.*)$", proc.stdout, flags=re.M)
    return (float(m.group(1)), [float(x) for x in reps.group(1).split()]) if m and reps else None


def apply_inproc_time(row, ctx, script_path, input_path, work, add=0.0):
    """For clouds up to --inproc-max-points: the row's time becomes the in-process time (plus `add`,
    the Ball Pivoting time a remeshing row builds on)."""
    if row["points"] > ctx.inproc_max_points:
        return
    t = inproc_time(ctx, script_path, input_path, work)
    if t is None:
        return
    row["time_in_process"], row["time_in_process_repeats"] = t[0], t[1]
    row["time"], row["time_source"] = t[0] + add, "in process"


def ply_face_count(path):
    with open(path, "rb") as f:
        head = f.read(4096).split(b"end_header")[0].decode("ascii", "replace")
    m = re.search(r"element face (\d+)", head)
    return int(m.group(1)) if m else 0


def repeated_runs(ctx, work, args):
    """ctx.repeat meshlabserver runs with `args` in `work`; None as soon as one fails."""
    runs = []
    for _ in range(ctx.repeat):
        r = run_meshlabserver(ctx, work, args, ctx.timeout)
        if r["rc"] != 0 or r["wall"] is None or r["rss_kb"] is None:
            return None
        runs.append(r)
    return runs


def repeats_for(ctx, cloud):
    """--repeat, or by default 3 runs on clouds up to 100k points and 1 above."""
    return ctx.repeat_option if ctx.repeat_option > 0 else (3 if cloud["points"] <= 100000 else 1)


def load_save(ctx, path, work):
    """A load+save-only run of `path`: its wall clock and peak memory are subtracted from the runs
    that load the same file."""
    runs = repeated_runs(ctx, work, ["-i", path, "-o", "loaded.ply", "-m", "fq"])
    if runs is None:
        raise SystemExit("meshlabserver cannot even load and save %s; see %s" % (path, work))
    best = min(runs, key=lambda r: r["wall"])
    return {"wall": best["wall"], "rss_kb": best["rss_kb"]}


# A filter that does nothing to a cloud: its run's peak is MeshLab's floor for applying any filter.
NOOP_MLX = """<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Select None">
  <Param type="RichBool" value="true" name="allFaces" description="" tooltip=""/>
  <Param type="RichBool" value="true" name="allVerts" description="" tooltip=""/>
 </filter>
</FilterScript>
"""


def noop_floor(ctx, path, work):
    """Peak memory (kB, the smallest of the repeats) of a run that loads `path`, applies a filter that
    does nothing ("Select None") and saves: MeshLab's cost of applying any filter (its filter
    environment, the script's parsing), which every filter pays on top of the load+save run."""
    os.makedirs(work, exist_ok=True)
    script = os.path.join(work, "noop.mlx")
    with open(script, "w") as f:
        f.write(NOOP_MLX)
    runs = repeated_runs(ctx, work, ["-i", path, "-o", "noop.ply", "-s", "noop.mlx"])
    if runs is None:
        log("  the no-op filter run failed on %s; see %s" % (path, work))
        return None
    return min(r["rss_kb"] for r in runs)


def baseline(cloud, ctx):
    base = load_save(ctx, cloud["path"], os.path.join(ctx.out, "runs", cloud["name"], "_load_save"))
    base["noop_rss_kb"] = noop_floor(ctx, cloud["path"], os.path.join(ctx.out, "runs", cloud["name"], "_noop"))
    return base


def measure_floors(rows, ctx, clouds=None):
    """The no-op filter floor of every saved cloud (or of `clouds`), stored in all its rows."""
    for name in sorted({r["cloud"] for r in rows}):
        if clouds and name not in clouds:
            continue
        cloud = prepare_cloud(name, ctx)
        if cloud is None:
            continue
        ctx.repeat = repeats_for(ctx, cloud)
        floor = noop_floor(ctx, cloud["path"], os.path.join(ctx.out, "runs", name, "_noop"))
        log("%s: no-op filter peak %s kB" % (name, floor))
        for r in rows:
            if r["cloud"] == name and floor is not None:
                r["noop_rss_kb"] = floor
    return rows


def extra_over_noop(r):
    """Extra peak per input point over the no-op filter run, or None."""
    if r.get("rss_kb") is None or r.get("noop_rss_kb") is None:
        return None
    return max(0, r["rss_kb"] - r["noop_rss_kb"]) * 1024.0 / r["points"]


def spherepack_log_info(log_text):
    """From the sphere packer's log: its d, the components it started and the points left with no
    vertex within d (the last values when the log holds several runs)."""
    info = {}
    dm = re.findall(r"Sphere Packing: .*?\bd = ([0-9.eE+-]+)", log_text)
    if dm:
        info["d"] = float(dm[-1])
    um = re.findall(r"Sphere Packing: (\d+) components? started, (\d+) points left with no vertex within d", log_text)
    if um:
        info["components_started"], info["unreached_points"] = int(um[-1][0]), int(um[-1][1])
    return info


def parse_key_values(text):
    """The "key: value" lines of build/g2s_run and build/afsr_run."""
    out = {}
    for line in text.splitlines():
        k, sep, v = line.partition(": ")
        if sep:
            out[k.strip()] = v.strip()
    return out


def run_afsr(cloud, ctx, row, work, edge_max):
    """The "cgal-afsr" row: build/afsr_run (CGAL's advancing front with its defaults) on the cloud,
    ctx.repeat times; the time is the tool's own of the reconstruction call alone, the fastest run's
    (its mesh is the one measured; the method is deterministic). Peak memory: the tool's own process
    (/usr/bin/time -v), per input point, kept apart from the meshlabserver rows' extra peak."""
    tool = ctx.tool("afsr_run")
    if not os.path.exists(tool):
        row["status"] = ("skipped: %s not built (CGAL not found at configure time: install libcgal-dev, "
                         "scripts/setup.sh, and configure again)" % tool)
        return row
    row["info"] = {}
    best = None
    for _ in range(ctx.repeat):
        tfile = os.path.join(work, "time.txt")
        cmd = ["/usr/bin/time", "-v", "-o", tfile, tool, cloud["path"], "-o", os.path.join(work, "mesh.ply")]
        try:
            proc = subprocess.run(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  universal_newlines=True, timeout=ctx.timeout)
        except subprocess.TimeoutExpired:
            row["status"] = "timed out after %d s" % ctx.timeout
            return row
        with open(os.path.join(work, "afsr_run.log"), "a") as f:
            f.write(proc.stdout)
        wall, rss, status = parse_time_report(tfile)
        kv = parse_key_values(proc.stdout)
        if proc.returncode != 0 or "seconds" not in kv:
            row["status"] = "failed: " + failure_reason(proc.stdout)
            return row
        run = {"seconds": float(kv["seconds"]), "total": float(kv["seconds_total"]), "wall": wall, "rss_kb": rss,
               "kv": kv}
        if best is None or run["seconds"] < best["seconds"]:
            best = run
    row.update({"wall": best["wall"], "rc": 0, "load_after": os.getloadavg()[0]})
    row["time"], row["time_source"] = best["seconds"], "afsr_run"
    row["info"].update({"seconds_total": best["total"], "cpu_seconds": float(best["kv"].get("cpu_seconds", "nan")),
                        "cgal_version": best["kv"].get("cgal_version"),
                        "unused_points": int(best["kv"].get("unused_points", 0)),
                        "tool_peak_rss_kb": best["rss_kb"],
                        "tool_peak_bytes_per_point": (best["rss_kb"] * 1024.0 / cloud["points"]
                                                      if best["rss_kb"] is not None else None)})
    mesh = os.path.join(work, "mesh.ply")
    if ply_face_count(mesh) == 0:
        row["status"] = "no faces in the mesh of afsr_run"
        return row
    row["status"] = "ok"
    measures = measure_mesh(ctx, mesh, cloud["path"], work, edge_max)
    if measures is None:
        row["status"] = "mesh_measures failed on the mesh"
        return row
    row["measures"] = measures
    row["edge_histogram_max"] = edge_max
    return row


def run_method(method, cloud, base, ctx, d_info, bpa_row=None):
    """Runs one method on one cloud and returns its row. "bpa_re" remeshes the mesh of `bpa_row`
    (Ball Pivoting with auto radius, already run on this cloud) when there is one, and counts
    Ball Pivoting's time plus the remeshing's; otherwise it runs both filters in one script."""
    work = os.path.join(ctx.out, "runs", cloud["name"], method)
    if os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(work)
    row = {"cloud": cloud["name"], "cloud_kind": cloud["kind"], "shape": cloud["shape"],
           "points": cloud["points"], "spacing": cloud["spacing"], "normals": cloud["normals"], "method": method,
           "label": METHODS[method][0], "run": ctx.run_stamp, "base_wall": base["wall"],
           "base_rss_kb": base["rss_kb"], "noop_rss_kb": base.get("noop_rss_kb"), "repeat": ctx.repeat, "load_before": os.getloadavg()[0],
           "perturbation": cloud.get("perturbation")}
    if method == AFSR:
        # The same edge histogram range as the other methods of the cloud.
        return run_afsr(cloud, ctx, row, work, edge_histogram_max(
            cloud["spacing"], d_info["d"] if "sphere packer" in d_info["source"] else 0))
    if (method in ("bpa", "bpa_re") and ctx.bpa_max_points and cloud["kind"] == "generated"
            and cloud["points"] > ctx.bpa_max_points):
        row["status"] = "skipped: generated cloud of more than %s points (--bpa-max-points)" % "{:,}".format(
            ctx.bpa_max_points)
        return row
    bpa_mesh = os.path.join(ctx.out, "runs", cloud["name"], "bpa", "mesh.ply")
    reuse = (method == "bpa_re" and bpa_row is not None and bpa_row.get("status") == "ok"
             and os.path.exists(bpa_mesh))
    if reuse:
        script = mlx([remesh_filter(d_info["d"], cloud["diagonal"])])
        info = {"remesh_target": d_info["d"], "remesh_target_source": d_info["source"],
                "remeshed": "the Ball Pivoting (auto radius) mesh of run %s" % bpa_row["run"]}
        input_path = os.path.join(work, "bpa.ply")
        shutil.copyfile(bpa_mesh, input_path)
        step_base = load_save(ctx, input_path, os.path.join(work, "_load_save"))
    else:
        script, info = method_script(method, cloud, ctx, d_info)
        input_path, step_base = cloud["path"], base
    row["info"] = info
    with open(os.path.join(work, "filter.mlx"), "w") as f:
        f.write(script)
    best = None
    for _ in range(ctx.repeat):
        r = run_meshlabserver(ctx, work, ["-i", input_path, "-o", "mesh.ply", "-m", "fq", "-s", "filter.mlx"],
                              ctx.timeout)
        if best is None or (r["rc"] == 0 and (best["rc"] != 0 or (r["wall"] or 1e30) < (best["wall"] or 1e30))):
            best = r
        if r["rc"] != 0:
            break
    r = best
    mesh = os.path.join(work, "mesh.ply")
    row.update({"wall": r["wall"], "rss_kb": r["rss_kb"], "rc": r["rc"], "load_after": os.getloadavg()[0]})
    if r["timed_out"]:
        row["status"] = "timed out after %d s" % ctx.timeout
        return row
    if r["rc"] != 0 or not os.path.exists(mesh):
        row["status"] = "failed: " + failure_reason(r["log"])
        return row
    if ply_face_count(mesh) == 0:
        row["status"] = ("no faces in the saved mesh (meshlabserver saves the current layer: is the new "
                         "layer current?): " + failure_reason(r["log"]))
        return row
    row["status"] = "ok"

    # Time: the filter's own log line for ours, wall clock minus load+save for MeshLab's.
    m = re.findall(r"(?:Sphere Packing|Robust G2S): time ([0-9.eE+-]+) s", r["log"])
    step = max(r["wall"] - step_base["wall"], 0.0)
    if method in OURS and m:
        row["time"], row["time_source"] = float(m[-1]), "filter log"
    elif reuse:
        row["time"], row["time_source"] = bpa_row["time"] + step, "wall - load/save"
        row["info"]["remesh_time"] = step
    else:
        row["time"], row["time_source"] = step, "wall - load/save"
    row["time_wall_minus_base"] = step
    if m and method in OURS:
        row["time_filter_log"] = float(m[-1])
    if not reuse:
        apply_inproc_time(row, ctx, os.path.join(work, "filter.mlx"), input_path, work)
    elif bpa_row.get("time_source") == "in process" or row["points"] <= ctx.inproc_max_points:
        apply_inproc_time(row, ctx, os.path.join(work, "filter.mlx"), input_path, work, add=bpa_row["time"])
    if method in SPHERE_PACKERS:
        row["info"].update(spherepack_log_info(r["log"]))
    if r["rss_kb"] is not None and base["rss_kb"] is not None:
        extra = max(0, r["rss_kb"] - base["rss_kb"]) * 1024.0 / cloud["points"]
        if reuse and bpa_row.get("extra_peak_bytes_per_point") is not None:
            extra = max(extra, bpa_row["extra_peak_bytes_per_point"])
        row["extra_peak_bytes_per_point"] = extra

    # The sphere packer's d of this run when there is one (its edges are >= d: a range from an
    # earlier d, or from the spacing alone, could leave them all above the histogram).
    hist_d = d_info["d"] if "sphere packer" in d_info["source"] else 0
    if method == "spherepack" and "d" in row["info"]:
        hist_d = row["info"]["d"]
    edge_max = edge_histogram_max(cloud["spacing"], hist_d)
    measures = measure_mesh(ctx, mesh, cloud["path"], work, edge_max)
    if measures is None:
        row["status"] = "mesh_measures failed on the mesh"
        return row
    row["measures"] = measures
    row["edge_histogram_max"] = edge_max
    return row


def remeasure(rows, ctx):
    """Measures every saved mesh again with the current build/mesh_measures (and the current
    histogram ranges), keeping the timings: for when the measures or histograms change."""
    clouds = {}
    for r in rows:
        if r.get("status") != "ok":
            continue
        if r["cloud"] not in clouds:
            clouds[r["cloud"]] = prepare_cloud(r["cloud"], ctx)
        cloud = clouds[r["cloud"]]
        if cloud is None:
            continue
        sp = next((x for x in rows if x["cloud"] == r["cloud"] and x["method"] == "spherepack"
                   and "d" in x.get("info", {})), None)
        edge_max = edge_histogram_max(cloud["spacing"], sp["info"]["d"] if sp else 0)
        work = os.path.join(ctx.out, "runs", r["cloud"], r["method"])
        measures = measure_mesh(ctx, os.path.join(work, "mesh.ply"), cloud["path"], work, edge_max)
        if measures is None:
            log("%s %s: mesh_measures failed, row kept as it was" % (r["cloud"], r["method"]))
            continue
        r["measures"], r["edge_histogram_max"] = measures, edge_max
        # Rows from before the unreached points were recorded: read them from the saved log.
        log_path = os.path.join(work, "meshlabserver.log")
        if r["method"] in SPHERE_PACKERS and os.path.exists(log_path):
            r.setdefault("info", {}).update(spherepack_log_info(open(log_path, errors="replace").read()))
        log("%s %s: measured again" % (r["cloud"], r["method"]))
    return rows


def retime(rows, ctx, clouds=None, methods=None):
    """Times again, in process, the rows of clouds up to --inproc-max-points (their meshes and
    memory kept): for rows measured before in-process timing existed."""
    for r in rows:
        if r.get("status") != "ok" or r["points"] > ctx.inproc_max_points or r["method"] in NOT_MESHLAB:
            continue
        if (clouds and r["cloud"] not in clouds) or (methods and r["method"] not in methods):
            continue
        work = os.path.join(ctx.out, "runs", r["cloud"], r["method"])
        cloud = prepare_cloud(r["cloud"], ctx)
        if cloud is None:
            continue
        add, input_path = 0.0, cloud["path"]
        if r["method"] == "bpa_re" and "remeshed" in r.get("info", {}):
            bpa = next((x for x in rows if x["cloud"] == r["cloud"] and x["method"] == "bpa"), None)
            if bpa is None or bpa.get("time_source") != "in process":
                continue
            add, input_path = bpa["time"], os.path.join(work, "bpa.ply")
        before = r.get("time")
        apply_inproc_time(r, ctx, os.path.join(work, "filter.mlx"), input_path, work, add=add)
        log("%s %s: %.4g s -> %.4g s (%s)" % (r["cloud"], r["method"], before or float("nan"), r["time"],
                                              r.get("time_source")))
    return rows


# --- Results --------------------------------------------------------------------------------

def load_rows(path):
    rows = []
    if os.path.exists(path):
        for line in open(path):
            line = line.strip()
            if line:
                rows.append(json.loads(line))
    return rows


def save_rows(path, rows):
    with open(path + ".tmp", "w") as f:
        for r in rows:
            f.write(json.dumps(r, sort_keys=True) + "\n")
    os.replace(path + ".tmp", path)


def merge_row(rows, row):
    rows = [r for r in rows if not (r["cloud"] == row["cloud"] and r["method"] == row["method"])]
    rows.append(row)
    return rows


def cloud_sort_key(name, rows):
    r = next(x for x in rows if x["cloud"] == name)
    kind_order = {"generated": 0, "data": 1, "file": 2}
    # A perturbed generated cloud (no shape of its own) sorts with its shape's clean clouds.
    shape = r.get("shape") or (name.split("-")[0] if r.get("cloud_kind") == "generated" else "")
    return (kind_order.get(r.get("cloud_kind"), 3), SHAPES.index(shape) if shape in SHAPES else 9, r["points"], name)


def fmt(v, spec):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "—"
    return format(v, spec)


TABLE_COLUMNS = ["method", "time [s]", "speed-up vs BPA", "vs BPA 3s", "faces", "triangles/s", "E_avg", "E_RMS %",
                 "Q_avg", "Q_RMS %", "QF", "μd %", "non-manifold V / E", "self-intersecting pairs",
                 "boundary edges", "holes", "components", "unreached points (components started)",
                 "extra peak [B/point]: over load+save / over no-op filter"]


def count_text(v):
    """A count of mesh_measures, "—" when this build of it does not report it."""
    return "—" if v is None else "{:,}".format(v)


def unreached_text(r):
    """The sphere packer's points left with no vertex within d (and the components it started)."""
    info = r.get("info", {})
    if r["method"] not in SPHERE_PACKERS or "unreached_points" not in info:
        return "—"
    return "%s (%s)" % ("{:,}".format(info["unreached_points"]), "{:,}".format(info["components_started"]))


def method_label(r):
    label = r["label"]
    info = r.get("info", {})
    if r["method"] == "bpa3" and "ball_radius" in info:
        label += " r=%.3g" % info["ball_radius"]
    if r["method"] == "bpa_re" and "remesh_target" in info:
        label += " d=%.3g" % info["remesh_target"]
        if "mean spacing" in info.get("remesh_target_source", ""):
            label += " (mean spacing: no sphere packer d)"
    if r["method"] in SPHERE_PACKERS and "d" in info:
        label += " d=%.3g" % info["d"]
    return label


def table(cloud_rows):
    ref = next((r for r in cloud_rows if r["method"] == REFERENCE and r.get("status") == "ok"), None)
    ref3 = next((r for r in cloud_rows if r["method"] == "bpa3" and r.get("status") == "ok"), None)
    lines = ["| " + " | ".join(TABLE_COLUMNS) + " |", "|" + "---|" * len(TABLE_COLUMNS)]
    order = {m: i for i, m in enumerate(TABLE_ORDER)}
    for r in sorted(cloud_rows, key=lambda x: order.get(x["method"], 99)):
        label = method_label(r)
        if r.get("status") != "ok":
            status = r.get("status", "?").replace("|", "/")
            if len(status) > 120:
                status = status[:117] + "..."
            lines.append("| %s | %s |" % (label, status) + " — |" * (len(TABLE_COLUMNS) - 2))
            continue
        m = r["measures"]
        t = r["time"]
        def speed(reference):
            return ("×%.2f" % (reference["time"] / t)) if reference and t > 0 and reference["time"] > 0 else "—"
        tps = m["faces"] / t if t > 0 else None
        cells = [label, fmt(t, "#.3g") + TIME_MARK.get(r["time_source"], "?"), speed(ref), speed(ref3),
                 "{:,}".format(m["faces"]), fmt(tps, ",.0f"), fmt(m["edge_mean"], ".4g"),
                 fmt(m["edge_rms_percent"], ".1f"), fmt(m["quality_mean"], ".4f"), fmt(m["quality_rms_percent"], ".1f"),
                 fmt(m["qf_mean"], ".4f"), fmt(m.get("mu_d_percent"), ".2f"),
                 "%d / %d" % (m["non_manifold_vertices"], m["non_manifold_edges"]),
                 count_text(m.get("self_intersecting_pairs")), "%d" % m["boundary_edges"], "%d" % m["boundary_loops"],
                 count_text(m.get("components")), unreached_text(r),
                 ("own process: %s" % fmt(r.get("info", {}).get("tool_peak_bytes_per_point"), ".0f")
                  if r["method"] in NOT_MESHLAB else
                  "%s / %s" % (fmt(r.get("extra_peak_bytes_per_point"), ".0f"), fmt(extra_over_noop(r), ".0f")))]
        assert len(cells) == len(TABLE_COLUMNS)
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def fit_slope(ns, ts):
    import numpy as np
    x, y = np.log10(np.array(ns, float)), np.log10(np.array(ts, float))
    slope, icept = np.polyfit(x, y, 1)
    return slope, icept


def read_hist(path):
    import numpy as np
    a = np.genfromtxt(path, delimiter=",", skip_header=1)
    return a[:, 0], a[:, 1], a[:, 2]


def plots(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    pdir = os.path.join(out, "plots")
    os.makedirs(pdir, exist_ok=True)
    made = []
    colors = {"bpa": "tab:gray", "bpa3": "tab:brown", "bpa_re": "tab:olive", "spherepack": "tab:blue",
              "spherepack25": "tab:cyan", "g2s": "tab:red", AFSR: "tab:green"}
    clouds = sorted({r["cloud"] for r in rows}, key=lambda n: cloud_sort_key(n, rows))
    for c in clouds:
        ok = [r for r in rows if r["cloud"] == c and r.get("status") == "ok"]
        if not ok:
            continue
        fig, axes = plt.subplots(1, 3, figsize=(13, 3.6))
        for r in sorted(ok, key=lambda x: RUN_ORDER.index(x["method"])):
            base = os.path.join(out, "runs", c, r["method"], "hist")
            for ax, kind in zip(axes, ["angles", "edges", "quality"]):
                p = "%s_%s.csv" % (base, kind)
                if not os.path.exists(p):
                    continue
                lo, hi, cnt = read_hist(p)
                total = cnt.sum()
                if total <= 0:
                    continue
                ax.step(lo, cnt / total, where="post", color=colors.get(r["method"]), label=METHODS[r["method"]][1],
                        linewidth=1.2, linestyle="--" if r["method"] == "spherepack25" else "-")
        axes[0].set_xlabel("angle [°]")
        axes[0].set_xlim(0, 180)
        axes[1].set_xlabel("edge length")
        axes[2].set_xlabel("Q_t")
        axes[2].set_xlim(0, 1)
        for ax in axes:
            ax.set_ylabel("fraction")
        axes[0].legend(fontsize=8)
        r0 = ok[0]
        fig.suptitle("%s (%s points): angles, edge lengths, triangle quality" % (c, "{:,}".format(r0["points"])))
        fig.tight_layout()
        p = os.path.join(pdir, "%s_histograms.png" % c)
        fig.savefig(p, dpi=80)
        plt.close(fig)
        made.append(p)

    # Time against points, per shape of the generated clouds, log-log with the fitted slope.
    shapes = [s for s in SHAPES if len({r["points"] for r in rows if r.get("shape") == s and r.get("status") == "ok"}) >= 2]
    slopes = {}
    if shapes:
        fig, axes = plt.subplots(1, len(shapes), figsize=(4.6 * len(shapes), 3.8), squeeze=False)
        for ax, s in zip(axes[0], shapes):
            for meth in RUN_ORDER:
                pts = sorted((r["points"], r["time"]) for r in rows
                             if r.get("shape") == s and r["method"] == meth and r.get("status") == "ok" and r["time"] > 0)
                if not pts:
                    continue
                ns, ts = zip(*pts)
                label = METHODS[meth][1]
                if len(pts) >= 2:
                    k, b = fit_slope(ns, ts)
                    slopes[(s, meth)] = k
                    xs = np.array([min(ns), max(ns)], float)
                    ax.plot(xs, 10 ** (b + k * np.log10(xs)), color=colors.get(meth), linewidth=0.8, linestyle="--")
                    label += " (slope %.2f)" % k
                ax.plot(ns, ts, "o", color=colors.get(meth), label=label, markersize=4)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("input points")
            ax.set_ylabel("time [s]")
            ax.set_title(s)
            ax.legend(fontsize=7)
            ax.grid(True, which="both", linewidth=0.3)
        fig.tight_layout()
        p = os.path.join(pdir, "scaling.png")
        fig.savefig(p, dpi=80)
        plt.close(fig)
        made.append(p)
    return made, slopes


def machine():
    def sh(cmd):
        try:
            return subprocess.run(cmd, shell=True, stdout=subprocess.PIPE, universal_newlines=True).stdout.strip()
        except OSError:
            return ""
    mem = sh("awk '/MemTotal/ {printf \"%.1f GiB\", $2/1048576}' /proc/meminfo")
    return {"nproc": sh("nproc"), "cpu": sh("lscpu | sed -n 's/^Model name: *//p' | head -1"), "memory": mem}


def load_range(rows):
    loads = [r[k] for r in rows for k in ("load_before", "load_after") if r.get(k) is not None]
    return "%.2f to %.2f" % (min(loads), max(loads)) if loads else "not recorded"


def repeat_text(rows):
    reps = sorted({r.get("repeat", 1) for r in rows})
    return " or ".join("%d×" % k for k in reps) + " (3× up to 100k points by default)"


TIME_MARK = {"in process": "", "filter log": "†", "wall - load/save": "*", "afsr_run": "‡"}
EXPLANATION = (
    "Time, unmarked: measured in process by `build/plugin_time` (every filter, ours and MeshLab's, on "
    "clouds up to 100k points): the plugin loaded and applied as meshlabserver does, one steady clock "
    "around applyFilter, the fastest of up to 5 repeats in one process, stopping once 3 s of filter time were spent. Marked †: our filter's own log line (`... time "
    "X s`, larger clouds). Marked *: MeshLab's filters on larger clouds, the wall clock of the "
    "meshlabserver run minus that of a load+save-only run of the same cloud (resolution 0.01 s). "
    "\"(Re)\": Ball Pivoting's time plus that of the remeshing on its mesh (3 "
    "iterations of Isotropic Explicit Remeshing at target length d, MeshLab's defaults otherwise). "
    "Marked ‡: CGAL's Advancing Front Surface Reconstruction (CGAL 5.5, Debian's libcgal-dev, with its "
    "defaults: radius_ratio_bound 5, beta 0.52), not a MeshLab filter: run by `build/afsr_run` "
    "(tools/cgal/afsr_run.cpp), one steady clock around the library call (its Delaunay triangulation "
    "included, reading and writing not), the fastest of the row's repeats; its memory column is the peak of "
    "afsr_run's own process per input point. "
    "Speed-up = time of Ball Pivoting (auto radius, or r = 3 × mean spacing) / time of the row. Extra "
    "peak = peak resident memory (/usr/bin/time -v) of the run minus that of the load+save-only run, "
    "per input point, and over that of a run applying a filter that does nothing (MeshLab's Select None: "
    "MeshLab's own cost of applying any filter, about 5 MB, which dominates on small clouds). μd % = mean distance of the input points to the mesh / their mean "
    "nearest-neighbour spacing × 100. Holes = boundary loops (non-manifold vertices split into their "
    "fans). Measures by `build/mesh_measures` (common/include/growth/mesh_measures.h).")


def header_lines(rows, command):
    mach = machine()
    runs = sorted({r["run"] for r in rows})
    return ["Command%s: `%s`  " % ("s" if "`; `" in command else "", command),
            "Machine: %s, `nproc` = %s, %s memory.  " % (mach["cpu"], mach["nproc"], mach["memory"]),
            "Run%s: %s. Load average (1 min) seen around the runs: %s.  " % (
                "s" if len(runs) > 1 else "", ", ".join(runs), load_range(rows)),
            "Each meshlabserver call was repeated %s and the fastest kept." % repeat_text(rows), "",
            EXPLANATION, ""]


def headline_section(clouds, rows, level):
    """One line per cloud: our filters' speed-ups against Ball Pivoting measured in the same run
    (time of Ball Pivoting / time of ours) and Robust G2S's triangle rate against Ball Pivoting's
    with r = 3 × spacing (both interpolate the points, so their face counts are comparable)."""
    def row_of(c, method):
        return next((r for r in rows if r["cloud"] == c and r["method"] == method and r.get("status") == "ok"), None)

    def ratio(num, den):
        return ("×%.1f" % (num / den)) if num and den and num > 0 and den > 0 else "—"

    def rate(r):
        return r["measures"]["faces"] / r["time"] if r and r["time"] > 0 else None

    if not any(row_of(c, "bpa") or row_of(c, "bpa3") for c in clouds):
        return []

    md = ["%s Headline: ratios against Ball Pivoting" % ("#" * level), "",
          "Speed-up = Ball Pivoting's time / our filter's time on the same cloud (above 1: "
          "ours is faster). Rates are per second of filter time: output vertices for the sphere packer, faces for "
          "Robust G2S.", "",
          "| cloud | points | Sphere Packing vs BPA auto | vs BPA 3s | Sphere Packing vertices/s "
          "| Robust G2S vs BPA auto | vs BPA 3s | G2S triangle rate / BPA 3s rate | G2S triangles/s |",
          "|---|" + "---|" * 8]
    for c in clouds:
        b, b3 = row_of(c, "bpa"), row_of(c, "bpa3")
        sp, g = row_of(c, "spherepack"), row_of(c, "g2s")
        if not (b or b3):
            continue
        pts = next(r for r in rows if r["cloud"] == c)["points"]
        t = lambda r: r["time"] if r else None
        vps = sp["measures"]["vertices"] / sp["time"] if sp and sp["time"] > 0 else None
        md.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            c, "{:,}".format(pts), ratio(t(b), t(sp)), ratio(t(b3), t(sp)), fmt(vps, ",.0f"), ratio(t(b), t(g)),
            ratio(t(b3), t(g)), ratio(rate(g), rate(b3)), fmt(rate(g), ",.0f")))
    md.append("")
    return md


def ok_row(rows, cloud, method):
    return next((r for r in rows if r["cloud"] == cloud and r["method"] == method and r.get("status") == "ok"), None)


def row_normals(r):
    """"own" or "meshlab" (rows from before the normals were recorded: from the cloud's name)."""
    return r.get("normals") or ("meshlab" if r["cloud"].endswith(ML_NORMALS_SUFFIX) else "own")


def timed(r):
    return fmt(r["time"], "#.3g") + TIME_MARK.get(r.get("time_source"), "?")


def peer_section(clouds, rows, level):
    """Robust G2S against CGAL's advancing front (issue 15: at most its holes on noisy clouds, with no
    non-manifold elements and no self-intersections, and faster), one line per cloud with both rows."""
    both = [c for c in clouds if ok_row(rows, c, "g2s") and ok_row(rows, c, AFSR)]
    if not both:
        return []
    md = ["%s Robust G2S against CGAL's advancing front" % ("#" * level), "",
          "Each cell: Robust G2S / CGAL's Advancing Front Surface Reconstruction (defaults) on the same cloud. "
          "Times as in the tables (Robust G2S: in process up to 100k points, the filter's log above; CGAL: "
          "afsr_run's clock around the library call, with its process CPU time in brackets: on a loaded "
          "machine the wall clock of a long run grows beyond it). Vertices: the input points the mesh uses (on the -out "
          "clouds, a mesher that uses more than the surface's points has meshed outliers in). Holes = boundary "
          "loops; noise in % of the clean cloud's mean spacing, outliers in % of its surface points.", "",
          "| cloud | points | time [s] | CGAL time / G2S time | faces | vertices | holes | boundary edges "
          "| non-manifold V / E | self-intersecting pairs | μd % | G2S holes ≤ CGAL's | same run |",
          "|---|" + "---|" * 12]

    def pair(g, a, key, spec=None):
        one = lambda m: count_text(m.get(key)) if spec is None else fmt(m.get(key), spec)
        return "%s / %s" % (one(g), one(a))

    for c in both:
        g, a = ok_row(rows, c, "g2s"), ok_row(rows, c, AFSR)
        gm, am = g["measures"], a["measures"]
        cpu = a.get("info", {}).get("cpu_seconds")
        md.append("| %s | %s | %s / %s%s | %s | %s | %s | %s | %s | %d / %d, %d / %d | %s | %s | %s | %s |" % (
            c, "{:,}".format(g["points"]), timed(g), timed(a), " (CPU %s)" % fmt(cpu, "#.3g") if cpu else "",
            ("×%.1f" % (a["time"] / g["time"])) if g["time"] > 0 else "—",
            pair(gm, am, "faces"), pair(gm, am, "vertices"), pair(gm, am, "boundary_loops"), pair(gm, am, "boundary_edges"),
            gm["non_manifold_vertices"], gm["non_manifold_edges"], am["non_manifold_vertices"], am["non_manifold_edges"],
            pair(gm, am, "self_intersecting_pairs"), pair(gm, am, "mu_d_percent", ".2f"),
            "yes" if gm["boundary_loops"] <= am["boundary_loops"] else "**no**",
            "yes" if g["run"] == a["run"] else "no (%s / %s)" % (g["run"], a["run"])))
    md.append("")
    return md


def real_scans_section(rows, level):
    """The sphere packer on the clouds of the data folder: own and MeshLab-estimated normals, at its
    default d and at d = 2.5 × the mean spacing."""
    scans = [(scan, n) for scan in DATA for n in (scan, scan + ML_NORMALS_SUFFIX)
             if any(r["cloud"] == n and r["method"] in SPHERE_PACKERS for r in rows)]
    if not scans:
        return []
    md = ["%s Sphere Packing on the real scans" % ("#" * level), "",
          "Each scan with its own normals and with MeshLab's (%s), at the filter's default d and at d = %.1f × "
          "the mean spacing. Unreached points: input points left with no vertex within d (in brackets: the "
          "components the growth started), from the filter's log. Self-intersecting pairs: \"—\" when this "
          "build of mesh_measures does not count them. vs BPA 3s: Ball Pivoting's (r = 3 × spacing) time / "
          "ours, on the same cloud." % (ML_NORMALS_TEXT, SPHEREPACK25_SPACINGS), "",
          "| scan | points | normals | d | time [s] | vs BPA 3s | non-manifold V / E | self-intersecting pairs "
          "| holes | components | unreached points (components started) | Q_avg | E_RMS % |",
          "|---|" + "---|" * 12]
    for scan, name in scans:
        b3 = ok_row(rows, name, "bpa3")
        for method in SPHERE_PACKERS:
            r = next((x for x in rows if x["cloud"] == name and x["method"] == method), None)
            if r is None:
                continue
            normals = "MeshLab" if row_normals(r) == "meshlab" else "own"
            d = r.get("info", {}).get("d")
            dtext = ("default" if method == "spherepack" else "%.1f × spacing" % SPHEREPACK25_SPACINGS) + (
                ", %.3g" % d if d else "")
            if r.get("status") != "ok":
                md.append("| %s | %s | %s | %s | %s |" % (scan, "{:,}".format(r["points"]), normals, dtext,
                                                         r.get("status", "?").replace("|", "/")[:120]) + " — |" * 8)
                continue
            m = r["measures"]
            vs = ("×%.2f" % (b3["time"] / r["time"])) if b3 and r["time"] > 0 and b3["time"] > 0 else "—"
            md.append("| %s | %s | %s | %s | %s | %s | %d / %d | %s | %d | %s | %s | %s | %s |" % (
                scan, "{:,}".format(r["points"]), normals, dtext, timed(r), vs, m["non_manifold_vertices"],
                m["non_manifold_edges"], count_text(m.get("self_intersecting_pairs")), m["boundary_loops"],
                count_text(m.get("components")), unreached_text(r), fmt(m["quality_mean"], ".4f"),
                fmt(m["edge_rms_percent"], ".1f")))
    md.append("")
    return md


SPEED_MIN_POINTS = 30000            # the speed check: clouds of at least this many points ...
SLOPE_RANGE = (10000, 1000000)      # ... and the time's log-log slope over these sizes ...
SLOPE_MAX = 1.1                     # ... at most this


def speed_section(rows, level):
    """The speed check of Sphere Packing at d = 2.5 × spacing: against Ball Pivoting (r = 3 × spacing)
    on every cloud of at least SPEED_MIN_POINTS points, and the log-log slope of its time over the
    generated clouds from 10k to 1M points, per shape."""
    sp = "spherepack25"
    clouds = sorted({r["cloud"] for r in rows if r["points"] >= SPEED_MIN_POINTS
                     and r["method"] in (sp, "bpa3")}, key=lambda n: cloud_sort_key(n, rows))
    if not clouds:
        return []
    md = ["%s Speed: Sphere Packing at d = %.1f × spacing against Ball Pivoting (r = 3 × spacing)" % (
              "#" * level, SPHEREPACK25_SPACINGS), "",
          "On every cloud of %s points or more: Ball Pivoting's time / ours (above 1: ours is faster), "
          "with the marks of the time column of the tables; \"same run\" says whether both rows come from "
          "one invocation. The target: faster on every such cloud, and a log–log slope of the time of at "
          "most %.1f from %s to %s points." % ("{:,}".format(SPEED_MIN_POINTS), SLOPE_MAX,
                                               size_label(SLOPE_RANGE[0]), size_label(SLOPE_RANGE[1])), "",
          "| cloud | points | %s [s] | %s [s] | BPA 3s / ours | faster | same run |" % (
              METHODS[sp][1], METHODS["bpa3"][1]),
          "|---|" + "---|" * 6]
    faster, slower, missing = [], [], []
    for c in clouds:
        a, b = ok_row(rows, c, sp), ok_row(rows, c, "bpa3")
        pts = next(r for r in rows if r["cloud"] == c)["points"]
        if not (a and b and a["time"] > 0):
            missing.append(c)
            md.append("| %s | %s | %s | %s | — | — | — |" % (c, "{:,}".format(pts), timed(a) if a else "no row",
                                                            timed(b) if b else "no row"))
            continue
        ratio = b["time"] / a["time"]
        (faster if ratio > 1 else slower).append(c)
        md.append("| %s | %s | %s | %s | ×%.2f | %s | %s |" % (
            c, "{:,}".format(pts), timed(a), timed(b), ratio, "yes" if ratio > 1 else "**no**",
            "yes" if a["run"] == b["run"] else "no (%s / %s)" % (a["run"], b["run"])))
    md += ["", "Faster than Ball Pivoting (r = 3 × spacing) on %d of %d clouds with both rows%s%s." % (
        len(faster), len(faster) + len(slower), "; not on: " + ", ".join(slower) if slower else "",
        "; without both rows: " + ", ".join(missing) if missing else ""), ""]

    # Slope over the generated clouds of SLOPE_RANGE, per shape: of the rows' time (the scaling plot's,
    # in process up to --inproc-max-points, the filter's log above) and of the filter's own log time
    # (one clock at every size).
    lo, hi = SLOPE_RANGE
    fits = []
    for s in SHAPES:
        pts = sorted((r["points"], r["time"], r.get("time_filter_log"), r.get("time_source")) for r in rows
                     if r.get("shape") == s and r["method"] == sp and r.get("status") == "ok"
                     and lo <= r["points"] <= hi and r["time"] > 0)
        if len({p[0] for p in pts}) < 2:
            continue
        k = fit_slope([p[0] for p in pts], [p[1] for p in pts])[0]
        logs = [p for p in pts if p[2]]
        kl = fit_slope([p[0] for p in logs], [p[2] for p in logs])[0] if len({p[0] for p in logs}) >= 2 else None
        full = pts[0][0] == lo and pts[-1][0] == hi
        fits.append("| %s | %s%s | %s | %s | %s |" % (
            s, ", ".join(size_label(p[0]) for p in pts), "" if full else " (not the whole range)",
            "%.2f%s" % (k, "" if k <= SLOPE_MAX else " **> %.1f**" % SLOPE_MAX),
            "—" if kl is None else "%.2f%s" % (kl, "" if kl <= SLOPE_MAX else " **> %.1f**" % SLOPE_MAX),
            ", ".join(sorted({p[3] for p in pts}))))
    if fits:
        md += ["Log–log slope of %s's time over the generated clouds from %s to %s points, per shape: of the "
               "tables' time, and of the filter's own log time (`Sphere Packing: time X s`, one clock at every "
               "size; the tables' time is in process up to --inproc-max-points)." % (
                   METHODS[sp][1], size_label(lo), size_label(hi)), "",
               "| shape | sizes | slope of the time | slope of the log time | time sources |", "|---|" + "---|" * 4]
        md += fits + [""]
    return md


def cloud_section(c, rows, level, image):
    """Markdown of one cloud: heading, table and (when `image` is not None) its histogram plot."""
    cr = [r for r in rows if r["cloud"] == c]
    r0 = cr[0]
    md = ["%s %s — %s points, mean spacing %.4g" % ("#" * level, c, "{:,}".format(r0["points"]), r0["spacing"]), "",
          table(cr), ""]
    if image:
        md += ["![%s: histograms of angles, edge lengths and Q_t](%s)" % (c, image), ""]
    return md


def memory_fits(rows):
    """Per (shape, method), over the generated clouds of at least 3 sizes: the least-squares line
    extra peak = F + b × points (extra peak over the load+save run, in bytes). Returns
    {(shape, method): (b [B/point], F [bytes], sizes)}."""
    import numpy as np
    fits = {}
    for s in SHAPES:
        for meth in RUN_ORDER:
            pts = sorted((r["points"], (r["rss_kb"] - r["base_rss_kb"]) * 1024.0) for r in rows
                         if r.get("shape") == s and r["method"] == meth and r.get("status") == "ok"
                         and r.get("rss_kb") is not None and r.get("base_rss_kb") is not None)
            if len({n for n, _ in pts}) >= 3:
                b, f = np.polyfit(np.array([n for n, _ in pts], float), np.array([e for _, e in pts], float), 1)
                fits[(s, meth)] = (b, f, len(pts))
    return fits


def scaling_section(slopes, level, image, fits=None):
    md = ["%s Time against number of points (log–log, fitted slope)" % ("#" * level), ""]
    if image:
        md += ["![time against points](%s)" % image, ""]
    if slopes:
        md.append("| shape | " + " | ".join(METHODS[m][1] for m in RUN_ORDER) + " |")
        md.append("|---|" + "---|" * len(RUN_ORDER))
        for s in SHAPES:
            if any(k[0] == s for k in slopes):
                md.append("| %s | " % s + " | ".join(
                    ("%.2f" % slopes[(s, m)]) if (s, m) in slopes else "—" for m in RUN_ORDER) + " |")
        md.append("")
    if fits:
        md += ["%s Memory against number of points (fitted line)" % ("#" * level), "",
               "Extra peak (over the load+save run) = F + b × points, least squares over the generated "
               "clouds' sizes: b [B/point] (F [MB]). F holds MeshLab's own cost of applying a filter "
               "(see the no-op column of the tables) and the filter's fixed costs.", "",
               "| shape | " + " | ".join(METHODS[m][1] for m in RUN_ORDER) + " |",
               "|---|" + "---|" * len(RUN_ORDER)]
        for s in SHAPES:
            if any(k[0] == s for k in fits):
                md.append("| %s | " % s + " | ".join(
                    ("%.0f (%.1f)" % (fits[(s, m)][0], fits[(s, m)][1] / 1e6)) if (s, m) in fits else "—"
                    for m in RUN_ORDER) + " |")
        md.append("")
    return md


def report(rows, ctx, command):
    made, slopes = plots(rows, ctx.out)
    clouds = sorted({r["cloud"] for r in rows}, key=lambda n: cloud_sort_key(n, rows))
    md = ["# Benchmark results", ""] + header_lines(rows, command) + headline_section(clouds, rows, 2)
    md += peer_section(clouds, rows, 2) + real_scans_section(rows, 2) + speed_section(rows, 2)
    for c in clouds:
        hp = os.path.join("plots", "%s_histograms.png" % c)
        md += cloud_section(c, rows, 2, hp if os.path.exists(os.path.join(ctx.out, hp)) else None)
    if slopes or os.path.exists(os.path.join(ctx.out, "plots", "scaling.png")):
        md += scaling_section(slopes, 2, "plots/scaling.png" if os.path.exists(os.path.join(ctx.out, "plots", "scaling.png")) else None,
                              memory_fits(rows))
    path = os.path.join(ctx.out, "results.md")
    with open(path, "w") as f:
        f.write("\n".join(md))
    return path, made, slopes


MAX_COMMITTED_PNG = 200 * 1024


def publish(rows, ctx, command, slopes):
    """Copies the plots (those under 200 KB) to docs/benchmark/, writes the full tables to
    docs/benchmark/results.md and the summary into README.md between the results markers (or,
    when the README has no markers, into docs/results.md)."""
    docs = os.path.join(ROOT, "docs", "benchmark")
    os.makedirs(docs, exist_ok=True)
    for old in os.listdir(docs):
        if old.endswith(".png"):
            os.remove(os.path.join(docs, old))
    clouds = sorted({r["cloud"] for r in rows}, key=lambda n: cloud_sort_key(n, rows))
    # Shown in the README: the clouds of the data folder and the largest generated cloud per shape.
    # Only their plots and the scaling plot are copied (each under 200 KB), to keep the repository small.
    shown = [c for c in clouds if next(r for r in rows if r["cloud"] == c)["cloud_kind"] != "generated"]
    for s in SHAPES:
        sized = [(r["points"], r["cloud"]) for r in rows if r.get("shape") == s]
        if sized:
            shown.append(max(sized)[1])
    shown = sorted(set(shown), key=lambda n: cloud_sort_key(n, rows))
    committed = set()
    pdir = os.path.join(ctx.out, "plots")
    for name in ["scaling.png"] + ["%s_histograms.png" % c for c in shown]:
        src = os.path.join(pdir, name)
        if os.path.exists(src) and os.path.getsize(src) < MAX_COMMITTED_PNG:
            shutil.copyfile(src, os.path.join(docs, name))
            committed.add(name)

    def image(name, relative_to):
        return os.path.relpath(os.path.join(docs, name), relative_to) if name in committed else None

    full = ["# Benchmark results", ""] + header_lines(rows, command) + headline_section(clouds, rows, 2)
    full += peer_section(clouds, rows, 2) + real_scans_section(rows, 2) + speed_section(rows, 2)
    for c in clouds:
        full += cloud_section(c, rows, 2, image("%s_histograms.png" % c, docs))
    full += scaling_section(slopes, 2, image("scaling.png", docs), memory_fits(rows))
    with open(os.path.join(docs, "results.md"), "w") as f:
        f.write("\n".join(full))

    readme = os.path.join(ROOT, "README.md")
    text = open(readme).read() if os.path.exists(readme) else ""
    begin, end = "<!-- results:begin -->", "<!-- results:end -->"
    into_readme = begin in text and end in text
    where = ROOT if into_readme else os.path.join(ROOT, "docs")
    summary = ["## Results", "",
               "Our filters against MeshLab's Ball Pivoting on the same clouds and the same machine "
               "(`scripts/benchmark.sh`; when the rows come from several invocations, each row's run is "
               "recorded in `out/benchmark/results.jsonl` and the runs are listed below). The ratios "
               "against Ball Pivoting are the headline; absolute seconds depend on the machine and its "
               "load.", ""] + header_lines(rows, command)
    summary += headline_section(clouds, rows, 3) + peer_section(clouds, rows, 3) + real_scans_section(rows, 3) + speed_section(rows, 3)
    for c in shown:
        summary += cloud_section(c, rows, 3, image("%s_histograms.png" % c, where) if c in ("bunny",) else None)
    summary += scaling_section(slopes, 3, image("scaling.png", where), memory_fits(rows))
    summary += ["Every cloud's table and histograms: [%s](%s)." % ("docs/benchmark/results.md",
                os.path.relpath(os.path.join(docs, "results.md"), where)), ""]
    if into_readme:
        head, rest = text.split(begin, 1)
        _, tail = rest.split(end, 1)
        with open(readme, "w") as f:
            f.write(head + begin + "\n" + "\n".join(summary) + end + tail)
        return readme
    path = os.path.join(ROOT, "docs", "results.md")
    with open(path, "w") as f:
        f.write("# Results\n\n" + "\n".join(summary[2:]))
    return path


# --- Main -----------------------------------------------------------------------------------

def expand_groups(specs, shapes):
    """The cloud groups of --clouds: "noisy" / "noisy-<size>" (every NOISE_LEVELS perturbation of every
    shape of --shapes, at NOISY_GROUP_SIZE points or <size>) and "scans" (the data folder's clouds
    with their own normals); other names stay as they are."""
    out = []
    for spec in specs:
        m = re.match(r"^noisy(?:-([0-9.]+[kKmM]?))?$", spec)
        if m:
            n = parse_size(m.group(1)) if m.group(1) else NOISY_GROUP_SIZE
            out += ["%s-%s-%s" % (s, size_label(n), p) for s in shapes for p in NOISE_LEVELS]
        elif spec == "scans":
            out += list(DATA)
        else:
            out.append(spec)
    return out


class Context:
    pass


def main():
    ap = argparse.ArgumentParser(prog="scripts/benchmark.sh", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="small clouds only (10k and 30k points, hand and hand-ml)")
    ap.add_argument("--methods", default=",".join(RUN_ORDER),
                    help="comma-separated subset of: " + ", ".join(RUN_ORDER))
    ap.add_argument("--clouds", default=None,
                    help="comma-separated clouds: sphere-10k, torus-1M, patch-30000, bunny, hand, horse, or .ply paths; "
                         "a name with -ml appended (bunny-ml, sphere-10k-ml) is that cloud with MeshLab's normals; "
                         "a generated one with -gauss<P> or -out<P> appended (torus-100k-gauss25, sphere-50k-out10) "
                         "has Gaussian noise of P %% of its mean spacing or P %% outliers; the groups noisy "
                         "(every shape of --shapes at 100k points, perturbed by each of " + ", ".join(NOISE_LEVELS) +
                         ") or noisy-<size>, and scans (the data folder's clouds) "
                         "(default: every shape at every size, and every cloud of the data folder with its own "
                         "normals and with MeshLab's)")
    ap.add_argument("--sizes", default=None, help="sizes of the generated clouds, e.g. 10k,100k,1M")
    ap.add_argument("--shapes", default=",".join(SHAPES), help="shapes of the generated clouds")
    ap.add_argument("--no-data", action="store_true", help="skip the clouds of the data folder")
    ap.add_argument("--param", action="append", default=[], metavar="METHOD:NAME=VALUE",
                    help="override a parameter of our filters' .mlx, e.g. spherepack:windowSize=4 (spherepack: "
                         "both sphere packer methods)")
    ap.add_argument("--bpa-max-points", type=int, default=0,
                    help="skip Ball Pivoting with auto radius (and its remeshing) on generated clouds larger "
                         "than this (it grows about quadratically on random samples); 0: no limit")
    ap.add_argument("--repeat", type=int, default=0,
                    help="run each meshlabserver call N times and keep the fastest; 0 (default): 3 times on "
                         "clouds up to 100k points, once above")
    ap.add_argument("--timeout", type=int, default=3 * 3600, help="seconds before a run is stopped")
    ap.add_argument("--report-only", action="store_true", help="only rebuild results.md and the plots")
    ap.add_argument("--remeasure", action="store_true",
                    help="measure every saved mesh again (measures and histograms), keeping the timings")
    ap.add_argument("--inproc-max-points", type=int, default=100000,
                    help="on clouds up to this many points, time every filter in process with build/plugin_time "
                         "(one clock around applyFilter, fastest of up to %d repeats) instead of the wall-clock "
                         "difference of meshlabserver runs (resolution 0.01 s); 0: never" % INPROC_REPEAT)
    ap.add_argument("--retime", action="store_true",
                    help="time the saved rows again in process (see --inproc-max-points), keeping meshes and "
                         "memory; restricted by --clouds and --methods when given")
    ap.add_argument("--floors", action="store_true",
                    help="measure the no-op filter floor (memory) of the saved rows' clouds again; restricted by "
                         "--clouds when given")
    ap.add_argument("--publish", action="store_true",
                    help="copy the plots (< 200 KB) and tables to docs/benchmark/ and the summary into "
                         "README.md between its results markers")
    ap.add_argument("--fresh", action="store_true", help="forget the rows of earlier invocations")
    ap.add_argument("--out", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--prefix", required=True)
    ap.add_argument("--data-dir", required=True)
    ap.add_argument("--command", default="scripts/benchmark.sh")
    a = ap.parse_args()

    ctx = Context()
    ctx.out, ctx.build, ctx.prefix, ctx.data_dir = (os.path.abspath(a.out), os.path.abspath(a.build),
                                                    os.path.abspath(a.prefix), os.path.abspath(a.data_dir))
    ctx.repeat_option, ctx.timeout = a.repeat, a.timeout
    ctx.bpa_max_points = a.bpa_max_points
    ctx.inproc_max_points = a.inproc_max_points
    ctx.tool = lambda name: os.path.join(ctx.build, name)
    ctx.run_stamp = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    ctx.params = {}
    for p in a.param:
        m = re.match(r"^(spherepack|spherepack25|g2s):([A-Za-z0-9_]+)=(.*)$", p)
        if not m:
            raise SystemExit("--param wants METHOD:NAME=VALUE with METHOD spherepack (both sphere packer "
                             "methods), spherepack25 or g2s, got '%s'" % p)
        ctx.params.setdefault(m.group(1), []).append((m.group(2), m.group(3)))
    os.makedirs(ctx.out, exist_ok=True)
    results = os.path.join(ctx.out, "results.jsonl")
    rows = [] if a.fresh else load_rows(results)

    if not a.report_only and not a.retime and not a.floors:
        methods = [m.strip() for m in a.methods.split(",") if m.strip()]
        for m in methods:
            if m not in METHODS:
                raise SystemExit("unknown method '%s' (choose from %s)" % (m, ", ".join(RUN_ORDER)))
        methods = [m for m in RUN_ORDER if m in methods]
        if a.clouds:
            specs = expand_groups([c.strip() for c in a.clouds.split(",") if c.strip()],
                                  [s.strip() for s in a.shapes.split(",") if s.strip()])
        else:
            sizes = [parse_size(s) for s in a.sizes.split(",")] if a.sizes else (QUICK_SIZES if a.quick else FULL_SIZES)
            shapes = [s.strip() for s in a.shapes.split(",") if s.strip()]
            specs = ["%s-%s" % (s, size_label(n)) for s in shapes for n in sizes]
            if not a.no_data:
                specs += QUICK_DATA_CLOUDS if a.quick else DATA_CLOUDS
        for spec in specs:
            cloud = prepare_cloud(spec, ctx)
            if cloud is None:
                log("%s: not in %s, skipped" % (spec, ctx.data_dir))
                continue
            ctx.repeat = repeats_for(ctx, cloud)
            log("%s: %d points, mean spacing %.4g" % (cloud["name"], cloud["points"], cloud["spacing"]))
            # The load+save and no-op runs only serve the methods run through meshlabserver.
            base = (baseline(cloud, ctx) if any(m not in NOT_MESHLAB for m in methods)
                    else {"wall": None, "rss_kb": None, "noop_rss_kb": None})
            # The remeshing target: the sphere packer's d from this run, else from an earlier row,
            # else the mean spacing (said so in the row).
            d_info = {"d": cloud["spacing"], "source": "mean spacing (no sphere packer d available)"}
            prev = next((r for r in rows if r["cloud"] == cloud["name"] and r["method"] == "spherepack"
                         and "d" in r.get("info", {})), None)
            if prev:
                d_info = {"d": prev["info"]["d"], "source": "sphere packer's d (%s)" % prev["run"]}
            for m in methods:
                log("%s: %s ..." % (cloud["name"], METHODS[m][0]))
                bpa_row = next((r for r in rows if r["cloud"] == cloud["name"] and r["method"] == "bpa"), None)
                row = run_method(m, cloud, base, ctx, d_info, bpa_row)
                if m == "spherepack" and "d" in row.get("info", {}):
                    d_info = {"d": row["info"]["d"], "source": "sphere packer's d (this run)"}
                if row["status"] == "ok":
                    mm = row["measures"]
                    log("  %s: %.3f s, %d faces, Q_avg %.4f, %d holes" % (row["status"], row["time"], mm["faces"],
                                                                         mm["quality_mean"] or 0, mm["boundary_loops"]))
                else:
                    log("  " + row["status"])
                rows = merge_row(rows, row)
                save_rows(results, rows)

    if not rows:
        raise SystemExit("no results yet")
    if a.remeasure:
        rows = remeasure(rows, ctx)
        save_rows(results, rows)
    if a.retime:
        only_clouds = [c.strip() for c in a.clouds.split(",")] if a.clouds else None
        only_methods = [m.strip() for m in a.methods.split(",")] if a.methods != ",".join(RUN_ORDER) else None
        rows = retime(rows, ctx, only_clouds, only_methods)
        save_rows(results, rows)
    if a.floors:
        rows = measure_floors(rows, ctx, [c.strip() for c in a.clouds.split(",")] if a.clouds else None)
        save_rows(results, rows)
    path, made, slopes = report(rows, ctx, a.command)
    log("tables: %s" % path)
    for p in made:
        log("plot: %s" % p)
    if a.publish:
        log("published: %s, docs/benchmark/" % publish(rows, ctx, a.command, slopes))


if __name__ == "__main__":
    main()
