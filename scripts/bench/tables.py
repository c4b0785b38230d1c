"""The Markdown of the results: the header (command, machine, date), the headline ratios against
Ball Pivoting, Robust G2S against CGAL, the real scans, the speed check, one table per cloud and
the scaling section."""
import math
import subprocess

from .config import (AFSR, DATA, METHODS, ML_NORMALS_SUFFIX, ML_NORMALS_TEXT, NOT_MESHLAB, REFERENCE, RUN_ORDER,
                     SHAPES, SPHERE_PACKERS, SPHEREPACK25_SPACINGS, TABLE_ORDER, size_label)
from .fits import fit_slope, memory_fits
from .measure import extra_over_noop
from .rows import cloud_sort_key, ok_row, row_normals


def fmt(v, spec):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "—"
    return format(v, spec)


TIME_MARK = {"in process": "", "filter log": "†", "wall - load/save": "*", "afsr_run": "‡"}
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


def timed(r):
    return fmt(r["time"], "#.3g") + TIME_MARK.get(r.get("time_source"), "?")


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
    """The header every results page starts with: the command that made it, the machine and the
    run's date (the dates, when the rows come from several invocations)."""
    mach = machine()
    runs = sorted({r["run"] for r in rows})
    return ["Command%s: `%s`  " % ("s" if "`; `" in command else "", command),
            "Machine: %s, `nproc` = %s, %s memory.  " % (mach["cpu"], mach["nproc"], mach["memory"]),
            "Date%s: %s.  " % ("s" if len(runs) > 1 else "", ", ".join(runs)),
            "Each meshlabserver call was repeated %s and the fastest kept." % repeat_text(rows), "",
            EXPLANATION, ""]


def headline_section(clouds, rows, level):
    """One line per cloud: our filters' speed-ups against Ball Pivoting measured in the same run
    (time of Ball Pivoting / time of ours) and Robust G2S's triangle rate against Ball Pivoting's
    with r = 3 × spacing (both interpolate the points, so their face counts are comparable)."""
    def ratio(num, den):
        return ("×%.1f" % (num / den)) if num and den and num > 0 and den > 0 else "—"

    def rate(r):
        return r["measures"]["faces"] / r["time"] if r and r["time"] > 0 else None

    if not any(ok_row(rows, c, "bpa") or ok_row(rows, c, "bpa3") for c in clouds):
        return []

    md = ["%s Headline: ratios against Ball Pivoting" % ("#" * level), "",
          "Speed-up = Ball Pivoting's time / our filter's time on the same cloud (above 1: "
          "ours is faster). Rates are per second of filter time: output vertices for the sphere packer, faces for "
          "Robust G2S.", "",
          "| cloud | points | Sphere Packing vs BPA auto | vs BPA 3s | Sphere Packing vertices/s "
          "| Robust G2S vs BPA auto | vs BPA 3s | G2S triangle rate / BPA 3s rate | G2S triangles/s |",
          "|---|" + "---|" * 8]
    for c in clouds:
        b, b3 = ok_row(rows, c, "bpa"), ok_row(rows, c, "bpa3")
        sp, g = ok_row(rows, c, "spherepack"), ok_row(rows, c, "g2s")
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


def peer_section(clouds, rows, level):
    """Robust G2S against CGAL's advancing front (the aim: at most its holes on noisy clouds, with no
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


def results_sections(rows, command, level, clouds, table_clouds, cloud_image, scaling_image, slopes,
                     with_scaling=True):
    """The sections of a results page at heading `level`: the header, the headline ratios, the peers,
    the real scans and the speed check over `clouds`; a table of each cloud of `table_clouds` (with
    the histograms image cloud_image(cloud), None for none); the scaling section (time slopes
    `slopes`, memory fits, image `scaling_image`) unless with_scaling is False."""
    md = header_lines(rows, command) + headline_section(clouds, rows, level) + peer_section(clouds, rows, level)
    md += real_scans_section(rows, level) + speed_section(rows, level)
    for c in table_clouds:
        md += cloud_section(c, rows, level, cloud_image(c))
    if with_scaling:
        md += scaling_section(slopes, level, scaling_image, memory_fits(rows))
    return md
