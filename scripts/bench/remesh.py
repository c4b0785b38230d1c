"""The remeshing benchmark (scripts/benchmark.sh --remesh): MeshLab's Isotropic Explicit Remeshing
(IER), CGAL's isotropic remeshing and our Sphere Packing remeshing on the same meshes at the same
absolute target length, each measured against its input.

    benchmark.sh --remesh [--meshes small|organic|medium|large|all|NAME,...] [--methods ier,cgal,ours]
                          [--target-scale F] [--plugin LIB.so] [--our-filter NAME] [--fresh] [--report-only]

Meshes (made once, kept in OUT/remesh/inputs/):
  SHAPE-SIZE     build/make_mesh --shape SHAPE --faces SIZE --seed 1 (box, cylinder, lprism, holedbox,
                 openbox, sheet; SIZE like 20k, 1m): CAD parts with creases, open meshes with holes
  bunny-g2s      build/g2s_run (Robust G2S, defaults) on DATA/bunny_merged_normals.ply: an organic scan
  scan-g2s-SIZE  build/make_cloud --shape scan --points SIZE --seed 1, then build/g2s_run
Groups: small = the six shapes at 20k faces; organic = bunny-g2s; medium = holedbox, cylinder, sheet at
200k faces; large = holedbox-1m and scan-g2s-600k (about 1.1M faces); all = all of these.

The target length L is F (--target-scale, 1 by default) times the input's mean edge length. Rows:
  ier   PyMeshLab 2025.7, meshing_isotropic_explicit_remeshing(iterations=3, targetlen=PureValue(L))
  cgal  build/isotropic_remesh_run --target L: CGAL 5.5 isotropic_remeshing, number_of_iterations(3),
        edges sharper than 30 degrees constrained (as IER's featuredeg 30)
  ours  the filter meshing_sphere_packing_remeshing of our plugin in PyMeshLab 2025.7, with d = L
        (skipped, with the reason, when the plugin has no such filter); the plugin is --plugin, else
        BUILD/meshlab-2025.07d/plugins/libfilter_spherepack.so when built, else the installed package's
Each method runs in a process of its own (scripts/bench/remesh_pymeshlab.py for the PyMeshLab rows);
the time is the wall time of the library call alone, the memory that process's peak RSS, also given
over its RSS with the input loaded. The output is measured by build/mesh_measures --reference INPUT
--target L. Writes OUT/remesh.md and OUT/remesh.jsonl (rows merged by mesh and method).
"""
import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys
import time

SHAPES = ("box", "cylinder", "lprism", "holedbox", "openbox", "sheet")
GROUPS = {
    "small": ["%s-20k" % s for s in SHAPES],
    "organic": ["bunny-g2s"],
    "medium": ["holedbox-200k", "cylinder-200k", "sheet-200k"],
    "large": ["holedbox-1m", "scan-g2s-600k"],
}
GROUPS["all"] = GROUPS["small"] + GROUPS["organic"] + GROUPS["medium"] + GROUPS["large"]
METHODS = {
    "ier": "MeshLab IER (3 iterations)",
    "cgal": "CGAL isotropic_remeshing (3 iterations)",
    "ours": "Sphere Packing remeshing (ours)",
}
LARGE_FACES = 100000   # the speed target applies from this many input faces
SIZE = re.compile(r"^(\d+)([km]?)$")
HERE = os.path.dirname(os.path.abspath(__file__))


def count(text):
    m = SIZE.match(text)
    if not m:
        raise SystemExit("remesh benchmark: bad size %r (like 20k, 1m)" % text)
    return int(m.group(1)) * {"": 1, "k": 1000, "m": 1000000}[m.group(2)]


def mesh_names(spec):
    names = []
    for part in spec.split(","):
        part = part.strip()
        if part:
            names.extend(GROUPS.get(part, [part]))
    return list(dict.fromkeys(names))


def run(cmd, timeout=None, **kw):
    return subprocess.run(cmd, check=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=timeout, **kw)


def key_values(text):
    out = {}
    for line in text.splitlines():
        k, sep, v = line.partition(": ")
        if sep:
            try:
                out[k.strip()] = float(v)
            except ValueError:
                out[k.strip()] = v.strip()
    return out


def make_input(name, a):
    """The input mesh NAME in OUT/remesh/inputs/ (made once) and how it was made."""
    folder = os.path.join(a.out, "remesh", "inputs")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, name + ".ply")
    kind, how = None, None
    parts = name.split("-")
    if len(parts) == 2 and parts[0] in SHAPES:
        kind = "open, holes" if parts[0] in ("openbox", "sheet") else "CAD, creases"
        if parts[0] == "openbox":
            kind = "CAD, creases, open"
        how = [os.path.join(a.build, "make_mesh"), "--shape", parts[0], "--faces", str(count(parts[1])), "--seed", "1", "-o", path]
        if not os.path.exists(path):
            run(how)
    elif name == "bunny-g2s":
        kind = "organic scan (Robust G2S mesh)"
        cloud = os.path.join(a.data_dir, "bunny_merged_normals.ply")
        if not os.path.exists(cloud):
            raise FileNotFoundError("no %s (--data-dir)" % cloud)
        how = [os.path.join(a.build, "g2s_run"), cloud, "-o", path]
        if not os.path.exists(path):
            run(how)
    elif len(parts) == 3 and parts[:2] == ["scan", "g2s"]:
        kind = "scan-like (Robust G2S mesh)"
        cloud = os.path.join(folder, "scan-%s-cloud.ply" % parts[2])
        make = [os.path.join(a.build, "make_cloud"), "--shape", "scan", "--points", str(count(parts[2])), "--seed", "1", "-o", cloud]
        how = make + ["&&", os.path.join(a.build, "g2s_run"), cloud, "-o", path]
        if not os.path.exists(path):
            run(make)
            run([os.path.join(a.build, "g2s_run"), cloud, "-o", path])
    else:
        raise SystemExit("remesh benchmark: unknown mesh %r (SHAPE-SIZE, bunny-g2s, scan-g2s-SIZE; groups %s)"
                         % (name, ", ".join(GROUPS)))
    return path, kind, " ".join(os.path.relpath(h, a.root) if os.path.isabs(h) and h.startswith(a.root) else h for h in how)


def measure(a, mesh, reference=None, target=None):
    cmd = [os.path.join(a.build, "mesh_measures"), mesh, "--no-min-vertex-distance"]
    if reference:
        cmd += ["--reference", reference]
    if target:
        cmd += ["--target", repr(target)]
    m = json.loads(run(cmd).stdout)
    for k in [k for k in m if k.startswith("histogram_")]:
        del m[k]
    return m


def run_method(method, a, inp, out, target):
    """Runs one method; a dict with status, seconds, load_rss_mib, peak_rss_mib and details."""
    if method == "cgal":
        tool = os.path.join(a.build, "isotropic_remesh_run")
        if not os.path.exists(tool):
            return {"status": "skipped: build/isotropic_remesh_run not built (no CGAL: scripts/setup.sh installs libcgal-dev)"}
        try:
            p = run([tool, inp, "--target", repr(target), "-o", out], timeout=a.timeout)
        except subprocess.CalledProcessError as e:
            return {"status": "failed: %s" % (e.stderr.strip().splitlines() or ["exit %d" % e.returncode])[-1]}
        kv = key_values(p.stdout)
        return {"status": "ok", "seconds": kv["seconds"], "load_rss_mib": kv["load_rss_mib"], "peak_rss_mib": kv["peak_rss_mib"],
                "detail": {k: kv[k] for k in ("remesh_seconds", "constrained_edges_after", "cgal_version", "soup_repaired") if k in kv}}
    if not a.python:
        return {"status": "skipped: no PyMeshLab (no venv: scripts/setup.sh --pymeshlab)"}
    cmd = [a.python, os.path.join(HERE, "remesh_pymeshlab.py"), method, inp, out, repr(target)]
    if method == "ours":
        if a.plugin:
            cmd += ["--plugin", a.plugin]
        cmd += ["--filter", a.our_filter]
    try:
        p = run(cmd, timeout=a.timeout)
    except subprocess.CalledProcessError as e:
        return {"status": "failed: %s" % (e.stderr.strip().splitlines() or ["exit %d" % e.returncode])[-1]}
    r = json.loads(p.stdout.strip().splitlines()[-1])
    return {"status": r.pop("status"), "seconds": r.pop("seconds", None), "load_rss_mib": r.pop("load_rss_mib", None),
            "peak_rss_mib": r.pop("peak_rss_mib", None), "detail": r}


def bench_mesh(name, a):
    inp, kind, how = make_input(name, a)
    m_in = measure(a, inp)
    target = a.target_scale * m_in["edge_mean"]
    rows = []
    for method in a.methods:
        folder = os.path.join(a.out, "remesh", name)
        os.makedirs(folder, exist_ok=True)
        out = os.path.join(folder, method + ".ply")
        if os.path.exists(out):
            os.remove(out)
        t0 = time.time()
        try:
            r = run_method(method, a, inp, out, target)
        except subprocess.TimeoutExpired:
            r = {"status": "failed: no result within %d s" % a.timeout}
        row = {"mesh": name, "method": method, "label": METHODS[method], "kind": kind, "input": os.path.relpath(inp, a.out),
               "made_by": how, "input_faces": m_in["faces"], "input_vertices": m_in["vertices"], "target": target,
               "target_scale": a.target_scale, "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
               "input_measures": m_in}
        row.update(r)
        if row["status"] == "ok":
            row["measures"] = measure(a, out, reference=inp, target=target)
        print("%-16s %-5s %s%s (%.0f s)" % (name, method, row["status"],
                                            " %.3f s" % row["seconds"] if row.get("seconds") is not None else "", time.time() - t0),
              flush=True)
        rows.append(row)
    return rows


# --- Report ---

def fmt(v, digits=3):
    if v is None:
        return "–"
    if isinstance(v, float):
        return "%.*f" % (digits, v)
    return "{:,}".format(v) if isinstance(v, int) else str(v)


def checks(rows):
    """The issue's targets for our row of one mesh: (mean Q_t >= IER's, every edge >= d, faster than
    IER's 3 iterations on inputs of 100k faces or more), each as (verdict, reason)."""
    by = {r["method"]: r for r in rows}
    ours, ier = by.get("ours"), by.get("ier")
    if not ours or ours["status"] != "ok":
        return None
    m = ours["measures"]
    out = []
    if ier and ier["status"] == "ok":
        q, qi = m["quality_mean"], ier["measures"]["quality_mean"]
        out.append(("mean Q_t >= IER's", "yes" if q >= qi else "NO", "%.4f vs %.4f" % (q, qi)))
    else:
        out.append(("mean Q_t >= IER's", "n/a", "no IER row"))
    below = m.get("edges_below_d", 0)
    out.append(("every edge >= d", "yes" if below == 0 else "NO",
                "shortest %.4f d, %d edges shorter than d" % (m["shortest_edge_over_d"], below)))
    if ours["input_faces"] < LARGE_FACES:
        out.append(("faster than IER", "n/a", "%s input faces < 100k" % fmt(ours["input_faces"])))
    elif ier and ier["status"] == "ok":
        out.append(("faster than IER", "yes" if ours["seconds"] < ier["seconds"] else "NO",
                    "%.3f s vs %.3f s" % (ours["seconds"], ier["seconds"])))
    else:
        out.append(("faster than IER", "n/a", "no IER row"))
    return out


HEADER = ("| method | time (s) | peak RSS MiB (over input) | faces | shortest edge / d | edges < d | E_avg / d | E_RMS % "
          "| mean Q_t | min Q_t | out→in mean / max (d) | in→out mean / max (d) | input vertices max (d) "
          "| components | boundary loops | genus | manifold | self-int. pairs |")


def row_line(label, r, m, target):
    def over(x):
        return None if x is None else x / target
    rss = "–"
    if r and r.get("peak_rss_mib") is not None:
        rss = "%.0f (%.0f)" % (r["peak_rss_mib"], r["peak_rss_mib"] - (r.get("load_rss_mib") or 0))
    seconds = fmt(r.get("seconds")) if r else "–"
    dist_out = dist_in = vmax = "–"
    if "to_reference_mean" in m:
        dist_out = "%.4f / %.4f" % (over(m["to_reference_mean"]), over(m["to_reference_max"]))
        dist_in = "%.4f / %.4f" % (over(m["from_reference_mean"]), over(m["from_reference_max"]))
        vmax = "%.4f" % over(m["from_reference_vertex_max"])
    genus = m["genus"] if m["genus"] >= 0 else "–"
    if m.get("genus_per_component") and len(m["genus_per_component"]) > 1:
        genus = "%s %s" % (genus, m["genus_per_component"][:5])
    return "| %s | %s | %s | %s | %s | %s | %s | %.1f | %.4f | %.4f | %s | %s | %s | %s | %s | %s | %s | %s |" % (
        label, seconds, rss, fmt(m["faces"]), fmt(over(m["edge_min"]), 4), fmt(m.get("edges_below_d", "–")),
        fmt(over(m["edge_mean"])), m["edge_rms_percent"], m["quality_mean"], m["quality_min"], dist_out, dist_in, vmax,
        fmt(m["components"]), fmt(m["boundary_loops"]), genus, "yes" if m["manifold"] else "no",
        fmt(m["self_intersecting_pairs"]))


def machine():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    mem = ""
    try:
        with open("/proc/meminfo") as f:
            mem = "%.0f GiB RAM" % (int(next(l.split()[1] for l in f if l.startswith("MemTotal"))) / 2**20)
    except (OSError, StopIteration):
        pass
    return "%s, %d cores, %s, %s %s" % (cpu, os.cpu_count() or 0, mem, platform.system(), platform.release())


def write_report(a, rows, commands):
    by_mesh = {}
    for r in rows:
        by_mesh.setdefault(r["mesh"], []).append(r)
    versions = sorted({"PyMeshLab " + r["detail"]["pymeshlab"] for r in rows if r.get("detail", {}).get("pymeshlab")} |
                      {"CGAL " + r["detail"]["cgal_version"] for r in rows if r.get("detail", {}).get("cgal_version")})
    lines = ["# Remeshing benchmark", "",
             "Commands (rows merged by mesh and method; each row's run in remesh.jsonl): " +
             "; ".join("`%s` (%s)" % (c, d) for c, d in commands.items()), "",
             "Date: %s. Machine: %s. %s." % (datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                                              machine(), ", ".join(versions) or "no peer versions recorded"), "",
             "d = the target length L given to every method (the input's mean edge length × the target scale). "
             "Time: wall time of the method's library call in its own process. Peak RSS: that process's peak "
             "resident set size, in brackets its growth over the input loaded. E_RMS: RMS deviation of the edge "
             "lengths in % of their mean; Q_t = 4√3 A / (l1² + l2² + l3²) (sphere-packing paper, sec. 5). "
             "Distances in units of d: out→in from the output's vertices and as many area-weighted random points "
             "(seed 1) as it has faces to the input's nearest triangle, in→out the other way; 'input vertices max' "
             "the largest distance of an input vertex to the output. Edges < d: shorter than d by more than float storage of their ends explains (2·√3·m·2^-24, m their largest coordinate). Genus "
             "from the Euler characteristic of each component (sum; the largest components' in brackets).", ""]
    summary, sections = [], []
    columns = HEADER.count("|") - 1
    for name, rs in by_mesh.items():
        rs.sort(key=lambda r: list(METHODS).index(r["method"]))
        r0 = rs[0]
        sections += ["## %s — %s faces, %s (d = %.6g)" % (name, fmt(r0["input_faces"]), r0["kind"], r0["target"]), "",
                     "Input: `%s`, made by `%s`." % (r0["input"], r0["made_by"]), "", HEADER, "|" + "---|" * columns,
                     row_line("input", None, r0["input_measures"], r0["target"])]
        for r in rs:
            if r["status"] == "ok":
                sections.append(row_line(r["label"], r, r["measures"], r["target"]))
            else:
                sections.append("| %s | %s |%s" % (r["label"], r["status"], " |" * (columns - 2)))
        c = checks(rs)
        sections.append("")
        if c:
            sections.append("Targets for ours: " + "; ".join("%s: **%s** (%s)" % t for t in c) + ".")
            summary.append("| %s | %s |" % (name, " | ".join("%s (%s)" % (t[1], t[2]) for t in c)))
        else:
            ours = next((r for r in rs if r["method"] == "ours"), None)
            sections.append("Targets for ours: not evaluated (%s)." % (ours["status"] if ours else "no row for ours"))
        sections.append("")
    if summary:
        lines += ["## Targets for ours, per mesh", "",
                  "| mesh | mean Q_t >= IER's | every edge >= d | faster than IER (>= 100k faces) |", "|---|---|---|---|"]
        lines += summary + [""]
    lines += sections
    path = os.path.join(a.out, "remesh.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--data-dir", required=True)
    ap.add_argument("--command", default="scripts/benchmark.sh --remesh")
    ap.add_argument("--python", help="the Python of the PyMeshLab venv (IER and our rows); none: those rows are skipped")
    ap.add_argument("--meshes", default="small")
    ap.add_argument("--methods", default="ier,cgal,ours")
    ap.add_argument("--target-scale", type=float, default=1.0, help="L = this × the input's mean edge length")
    ap.add_argument("--plugin", help="our libfilter_spherepack.so for PyMeshLab 2025.7 (default: BUILD/meshlab-2025.07d/plugins/"
                    "libfilter_spherepack.so when built, else the installed growth_meshers package's)")
    ap.add_argument("--our-filter", default="meshing_sphere_packing_remeshing")
    ap.add_argument("--timeout", type=int, default=900, help="seconds per run")
    ap.add_argument("--fresh", action="store_true", help="forget the rows of earlier runs")
    ap.add_argument("--report-only", action="store_true", help="write remesh.md again from remesh.jsonl, running nothing")
    a = ap.parse_args(argv)
    a.root = os.path.dirname(os.path.dirname(HERE))
    a.build, a.out = os.path.abspath(a.build), os.path.abspath(a.out)
    a.methods = [m.strip() for m in a.methods.split(",") if m.strip()]
    # Our plugin: the build's PyMeshLab 2025.7 one when it was built (-DGROWTH_MESHLAB_2025D=ON), else
    # the installed growth_meshers package's.
    built = os.path.join(a.build, "meshlab-2025.07d", "plugins", "libfilter_spherepack.so")
    if not a.plugin and os.path.exists(built):
        a.plugin = built
    for m in a.methods:
        if m not in METHODS:
            raise SystemExit("remesh benchmark: unknown method %r (%s)" % (m, ", ".join(METHODS)))
    if not a.target_scale > 0:
        raise SystemExit("remesh benchmark: --target-scale must be positive")
    for tool in ("make_mesh", "mesh_measures"):
        if not os.path.exists(os.path.join(a.build, tool)):
            raise SystemExit("remesh benchmark: no %s/%s: build it first" % (a.build, tool))
    os.makedirs(a.out, exist_ok=True)
    jsonl = os.path.join(a.out, "remesh.jsonl")
    old = []
    if os.path.exists(jsonl) and not a.fresh:
        with open(jsonl) as f:
            old = [json.loads(l) for l in f if l.strip()]
    new = []
    for name in [] if a.report_only else mesh_names(a.meshes):
        for r in bench_mesh(name, a):
            r["command"] = a.command
            new.append(r)
    done = {(r["mesh"], r["method"]) for r in new}
    rows = [r for r in old if (r["mesh"], r["method"]) not in done] + new
    with open(jsonl, "w") as f:
        for r in rows:
            f.write(json.dumps(r) + "\n")
    # Each command with the date of its first row: rows merged from several runs say which run made them.
    commands = {}
    for r in rows:
        commands.setdefault(r["command"], r["date"])
    print("wrote", write_report(a, rows, commands))
    return 0


if __name__ == "__main__":
    sys.exit(main())
