"""The rows: one method run on one cloud (our filters and Ball Pivoting through meshlabserver, CGAL's
advancing front through build/afsr_run), timed and measured; and the reruns of saved rows
(--retime, --floors)."""
import os
import re
import shutil
import subprocess

from .clouds import prepare_cloud
from .config import AFSR, METHODS, NOT_MESHLAB, OURS, SPHERE_PACKERS, log
from .filter_scripts import method_script, mlx, remesh_filter
from .measure import edge_histogram_max, measure_mesh, ply_face_count, spherepack_log_info
from .meshlabserver import failure_reason, load_save, noop_floor, parse_time_report, repeats_for, run_meshlabserver
from .timing import apply_inproc_time


def parse_key_values(text):
    """The "key: value" lines of build/g2s_run and build/afsr_run."""
    out = {}
    for line in text.splitlines():
        k, sep, v = line.partition(": ")
        if sep:
            out[k.strip()] = v.strip()
    return out


def new_row(method, cloud, base, ctx):
    """The fields every row has before its method runs: the cloud, the method, the run, the baseline."""
    return {"cloud": cloud["name"], "cloud_kind": cloud["kind"], "shape": cloud["shape"],
            "points": cloud["points"], "spacing": cloud["spacing"], "normals": cloud["normals"], "method": method,
            "label": METHODS[method][0], "run": ctx.run_stamp, "base_wall": base["wall"],
            "base_rss_kb": base["rss_kb"], "noop_rss_kb": base.get("noop_rss_kb"), "repeat": ctx.repeat,
            "load_before": os.getloadavg()[0], "perturbation": cloud.get("perturbation")}


def histogram_edge_max(row, cloud, d_info):
    """The edge histograms' range of a row, the same for every method of a cloud: from the sphere
    packer's d when there is one, that of this very row for "spherepack" (its edges are >= d: a
    range from an earlier d, or from the spacing alone, could leave them all above the histogram)."""
    d = d_info["d"] if "sphere packer" in d_info["source"] else 0
    if row["method"] == "spherepack" and "d" in row.get("info", {}):
        d = row["info"]["d"]
    return edge_histogram_max(cloud["spacing"], d)


def with_measures(row, ctx, cloud, work, d_info):
    """Ends a row whose run saved a mesh with faces (work/mesh.ply): its measures and histograms by
    build/mesh_measures, or the status that says the tool failed."""
    edge_max = histogram_edge_max(row, cloud, d_info)
    measures = measure_mesh(ctx, os.path.join(work, "mesh.ply"), cloud["path"], work, edge_max)
    if measures is None:
        row["status"] = "mesh_measures failed on the mesh"
        return row
    row["measures"] = measures
    row["edge_histogram_max"] = edge_max
    return row


def best_afsr_run(tool, cloud, ctx, work):
    """ctx.repeat runs of build/afsr_run under /usr/bin/time -v; the fastest by the tool's own clock,
    or a status text when a run timed out or failed."""
    best = None
    for _ in range(ctx.repeat):
        tfile = os.path.join(work, "time.txt")
        cmd = ["/usr/bin/time", "-v", "-o", tfile, tool, cloud["path"], "-o", os.path.join(work, "mesh.ply")]
        try:
            proc = subprocess.run(cmd, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  universal_newlines=True, timeout=ctx.timeout)
        except subprocess.TimeoutExpired:
            return "timed out after %d s" % ctx.timeout
        with open(os.path.join(work, "afsr_run.log"), "a") as f:
            f.write(proc.stdout)
        wall, rss, _ = parse_time_report(tfile)
        kv = parse_key_values(proc.stdout)
        if proc.returncode != 0 or "seconds" not in kv:
            return "failed: " + failure_reason(proc.stdout)
        run = {"seconds": float(kv["seconds"]), "total": float(kv["seconds_total"]), "wall": wall, "rss_kb": rss,
               "kv": kv}
        if best is None or run["seconds"] < best["seconds"]:
            best = run
    return best


def run_afsr(cloud, ctx, row, work, d_info):
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
    best = best_afsr_run(tool, cloud, ctx, work)
    if isinstance(best, str):
        row["status"] = best
        return row
    row.update({"wall": best["wall"], "rc": 0, "load_after": os.getloadavg()[0]})
    row["time"], row["time_source"] = best["seconds"], "afsr_run"
    row["info"].update({"seconds_total": best["total"], "cpu_seconds": float(best["kv"].get("cpu_seconds", "nan")),
                        "cgal_version": best["kv"].get("cgal_version"),
                        "unused_points": int(best["kv"].get("unused_points", 0)),
                        "tool_peak_rss_kb": best["rss_kb"],
                        "tool_peak_bytes_per_point": (best["rss_kb"] * 1024.0 / cloud["points"]
                                                      if best["rss_kb"] is not None else None)})
    if ply_face_count(os.path.join(work, "mesh.ply")) == 0:
        row["status"] = "no faces in the mesh of afsr_run"
        return row
    row["status"] = "ok"
    return with_measures(row, ctx, cloud, work, d_info)


def meshlab_input(method, cloud, base, ctx, d_info, bpa_row, work):
    """The filter script of a meshlabserver row (written to work/filter.mlx), its info, the input it
    runs on and the load+save run to subtract. "bpa_re" remeshes the saved mesh of `bpa_row` when
    there is one (reuse = True); otherwise its script runs both filters."""
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
    with open(os.path.join(work, "filter.mlx"), "w") as f:
        f.write(script)
    return info, input_path, step_base, reuse


def best_meshlabserver_run(ctx, work, input_path):
    """ctx.repeat meshlabserver runs of work/filter.mlx on `input_path`, stopping at the first that
    fails; the fastest successful one, else the failed one."""
    best = None
    for _ in range(ctx.repeat):
        r = run_meshlabserver(ctx, work, ["-i", input_path, "-o", "mesh.ply", "-m", "fq", "-s", "filter.mlx"],
                              ctx.timeout)
        if best is None or (r["rc"] == 0 and (best["rc"] != 0 or (r["wall"] or 1e30) < (best["wall"] or 1e30))):
            best = r
        if r["rc"] != 0:
            break
    return best


def set_meshlab_time(row, r, ctx, work, input_path, step_base, bpa_row):
    """The time of a meshlabserver row: in process (build/plugin_time) up to --inproc-max-points;
    above, the filter's own log line for ours and the wall clock minus load+save for MeshLab's.
    A reused "bpa_re" counts Ball Pivoting's time plus the remeshing's (bpa_row is then its row)."""
    method, reuse = row["method"], "remeshed" in row["info"]
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


def run_method(method, cloud, base, ctx, d_info, bpa_row=None):
    """Runs one method on one cloud and returns its row. "bpa_re" remeshes the mesh of `bpa_row`
    (Ball Pivoting with auto radius, already run on this cloud) when there is one, and counts
    Ball Pivoting's time plus the remeshing's; otherwise it runs both filters in one script."""
    work = os.path.join(ctx.out, "runs", cloud["name"], method)
    if os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(work)
    row = new_row(method, cloud, base, ctx)
    if method == AFSR:
        return run_afsr(cloud, ctx, row, work, d_info)
    if (method in ("bpa", "bpa_re") and ctx.bpa_max_points and cloud["kind"] == "generated"
            and cloud["points"] > ctx.bpa_max_points):
        row["status"] = "skipped: generated cloud of more than %s points (--bpa-max-points)" % "{:,}".format(
            ctx.bpa_max_points)
        return row
    row["info"], input_path, step_base, reuse = meshlab_input(method, cloud, base, ctx, d_info, bpa_row, work)
    r = best_meshlabserver_run(ctx, work, input_path)
    row.update({"wall": r["wall"], "rss_kb": r["rss_kb"], "rc": r["rc"], "load_after": os.getloadavg()[0]})
    if r["timed_out"]:
        row["status"] = "timed out after %d s" % ctx.timeout
        return row
    if r["rc"] != 0 or not os.path.exists(os.path.join(work, "mesh.ply")):
        row["status"] = "failed: " + failure_reason(r["log"])
        return row
    if ply_face_count(os.path.join(work, "mesh.ply")) == 0:
        row["status"] = ("no faces in the saved mesh (meshlabserver saves the current layer: is the new "
                         "layer current?): " + failure_reason(r["log"]))
        return row
    row["status"] = "ok"
    set_meshlab_time(row, r, ctx, work, input_path, step_base, bpa_row)
    if method in SPHERE_PACKERS:
        row["info"].update(spherepack_log_info(r["log"]))
    # Memory: the extra peak over the load+save run, per input point (a reused "bpa_re": at least
    # Ball Pivoting's).
    if r["rss_kb"] is not None and base["rss_kb"] is not None:
        extra = max(0, r["rss_kb"] - base["rss_kb"]) * 1024.0 / cloud["points"]
        if reuse and bpa_row.get("extra_peak_bytes_per_point") is not None:
            extra = max(extra, bpa_row["extra_peak_bytes_per_point"])
        row["extra_peak_bytes_per_point"] = extra
    return with_measures(row, ctx, cloud, work, d_info)


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
