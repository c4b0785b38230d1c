"""Writing the results: OUT/results.md with the plots, and with --publish docs/benchmark/ and the
README's results section."""
import os
import shutil

from .config import ROOT, SHAPES
from .plots import plots
from .rows import cloud_sort_key, sorted_clouds
from .tables import results_sections


def report(rows, ctx, command):
    """Writes the plots and OUT/results.md; returns its path, the plots and the fitted time slopes."""
    made, slopes = plots(rows, ctx.out)
    clouds = sorted_clouds(rows)

    def plot(name):
        return os.path.join("plots", name) if os.path.exists(os.path.join(ctx.out, "plots", name)) else None

    md = ["# Benchmark results", ""] + results_sections(
        rows, command, 2, clouds, clouds, lambda c: plot("%s_histograms.png" % c), plot("scaling.png"), slopes,
        with_scaling=bool(slopes) or plot("scaling.png") is not None)
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
    clouds = sorted_clouds(rows)
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

    full = ["# Benchmark results", ""] + results_sections(
        rows, command, 2, clouds, clouds, lambda c: image("%s_histograms.png" % c, docs), image("scaling.png", docs),
        slopes)
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
               "load.", ""]
    # In the README, only the bunny's histograms.
    summary += results_sections(
        rows, command, 3, clouds, shown, lambda c: image("%s_histograms.png" % c, where) if c == "bunny" else None,
        image("scaling.png", where), slopes)
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
