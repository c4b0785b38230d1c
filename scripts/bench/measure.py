"""Measuring a mesh with build/mesh_measures (measures and histograms), what the sphere packer's
log says, the extra peak memory of a row, and measuring the saved meshes again."""
import json
import os
import re
import subprocess

from .clouds import prepare_cloud
from .config import SPHERE_PACKERS, log


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


def ply_face_count(path):
    with open(path, "rb") as f:
        head = f.read(4096).split(b"end_header")[0].decode("ascii", "replace")
    m = re.search(r"element face (\d+)", head)
    return int(m.group(1)) if m else 0


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


def extra_over_noop(r):
    """Extra peak per input point over the no-op filter run, or None."""
    if r.get("rss_kb") is None or r.get("noop_rss_kb") is None:
        return None
    return max(0, r["rss_kb"] - r["noop_rss_kb"]) * 1024.0 / r["points"]


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
