"""Running the scratch meshlabserver under xvfb-run and /usr/bin/time -v: wall clock, peak memory,
the reason of a failure; the load+save-only and no-op runs whose cost is subtracted."""
import os
import subprocess

from .config import log
from .filter_scripts import NOOP_MLX


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
