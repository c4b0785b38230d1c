"""The command line of scripts/benchmark.py (scripts/benchmark.sh): the options, then runs the
clouds and methods asked for, reruns saved rows, and writes the report."""
import argparse
import datetime
import os
import re

from .clouds import prepare_cloud
from .config import (DATA_CLOUDS, FULL_SIZES, METHODS, NOISE_LEVELS, NOT_MESHLAB, QUICK_DATA_CLOUDS, QUICK_SIZES,
                     RUN_ORDER, SHAPES, expand_groups, log, parse_size, size_label)
from .measure import remeasure
from .meshlabserver import baseline, repeats_for
from .report import publish, report
from .rows import load_rows, merge_row, save_rows
from .runners import measure_floors, retime, run_method
from .timing import INPROC_REPEAT


class Context:
    """What every step needs: the folders (out, build, prefix, data_dir), the tool paths (tool(name)),
    the run's options (repeat, timeout, bpa_max_points, inproc_max_points, params) and its stamp."""


def comma_list(text):
    """The non-empty, stripped items of a comma-separated option."""
    return [x.strip() for x in text.split(",") if x.strip()]


def parse_args(description):
    ap = argparse.ArgumentParser(prog="scripts/benchmark.sh", description=description,
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
                    help="write the tables to docs/benchmark/results.md and copy the plots it shows (< 200 KB) "
                         "there, replacing the previous publication")
    ap.add_argument("--fresh", action="store_true", help="forget the rows of earlier invocations")
    ap.add_argument("--out", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--prefix", required=True)
    ap.add_argument("--data-dir", required=True)
    ap.add_argument("--command", default="scripts/benchmark.sh")
    return ap.parse_args()


def make_context(a):
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
    return ctx


def chosen_methods(a):
    """The methods of --methods, in RUN_ORDER."""
    methods = comma_list(a.methods)
    for m in methods:
        if m not in METHODS:
            raise SystemExit("unknown method '%s' (choose from %s)" % (m, ", ".join(RUN_ORDER)))
    return [m for m in RUN_ORDER if m in methods]


def cloud_specs(a):
    """The clouds to run: --clouds with its groups expanded, else every shape of --shapes at every size
    (--sizes, or those of --quick) and, unless --no-data, the data folder's clouds."""
    shapes = comma_list(a.shapes)
    if a.clouds:
        return expand_groups(comma_list(a.clouds), shapes)
    sizes = [parse_size(s) for s in comma_list(a.sizes)] if a.sizes else (QUICK_SIZES if a.quick else FULL_SIZES)
    specs = ["%s-%s" % (s, size_label(n)) for s in shapes for n in sizes]
    if not a.no_data:
        specs += QUICK_DATA_CLOUDS if a.quick else DATA_CLOUDS
    return specs


def run_cloud(spec, methods, rows, ctx, results):
    """Runs `methods` on the cloud `spec`, merging each row into `rows` and results.jsonl as it
    comes; returns the rows."""
    cloud = prepare_cloud(spec, ctx)
    if cloud is None:
        log("%s: not in %s, skipped" % (spec, ctx.data_dir))
        return rows
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
    return rows


def main(description):
    """Runs the benchmark with the command line of scripts/benchmark.sh; `description` is the --help
    text (scripts/benchmark.py's docstring)."""
    a = parse_args(description)
    ctx = make_context(a)
    os.makedirs(ctx.out, exist_ok=True)
    results = os.path.join(ctx.out, "results.jsonl")
    rows = [] if a.fresh else load_rows(results)

    if not a.report_only and not a.retime and not a.floors:
        methods = chosen_methods(a)
        for spec in cloud_specs(a):
            rows = run_cloud(spec, methods, rows, ctx, results)

    if not rows:
        raise SystemExit("no results yet")
    only_clouds = comma_list(a.clouds) if a.clouds else None
    if a.remeasure:
        rows = remeasure(rows, ctx)
        save_rows(results, rows)
    if a.retime:
        only_methods = comma_list(a.methods) if a.methods != ",".join(RUN_ORDER) else None
        rows = retime(rows, ctx, only_clouds, only_methods)
        save_rows(results, rows)
    if a.floors:
        rows = measure_floors(rows, ctx, only_clouds)
        save_rows(results, rows)
    path, made, slopes = report(rows, ctx, a.command)
    log("tables: %s" % path)
    for p in made:
        log("plot: %s" % p)
    if a.publish:
        log("published: %s, docs/benchmark/" % publish(rows, ctx, a.command, slopes))
