"""The plots: per cloud, the histograms of angles, edge lengths and Q_t of every method; time
against points (log-log, fitted slope)."""
import os

from .config import AFSR, METHODS, RUN_ORDER, SHAPES
from .fits import fit_slope
from .rows import sorted_clouds


def read_hist(path):
    import numpy as np
    a = np.genfromtxt(path, delimiter=",", skip_header=1)
    return a[:, 0], a[:, 1], a[:, 2]


COLORS = {"bpa": "tab:gray", "bpa3": "tab:brown", "bpa_re": "tab:olive", "spherepack": "tab:blue",
          "spherepack25": "tab:cyan", "g2s": "tab:red", AFSR: "tab:green"}


def save_figure(plt, fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return path


def plots(rows, out):
    """Writes OUT/plots/<cloud>_histograms.png for every cloud with a measured row and, when a shape
    has rows at two sizes or more, OUT/plots/scaling.png; returns the plots and the fitted slopes
    {(shape, method): slope}."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    pdir = os.path.join(out, "plots")
    os.makedirs(pdir, exist_ok=True)
    made = []
    for c in sorted_clouds(rows):
        ok = [r for r in rows if r["cloud"] == c and r.get("status") == "ok"]
        if ok:
            made.append(histograms_plot(plt, c, ok, out, os.path.join(pdir, "%s_histograms.png" % c)))
    slopes = {}
    shapes = [s for s in SHAPES if len({r["points"] for r in rows if r.get("shape") == s and r.get("status") == "ok"}) >= 2]
    if shapes:
        made.append(scaling_plot(plt, rows, shapes, slopes, os.path.join(pdir, "scaling.png")))
    return made, slopes


def histograms_plot(plt, c, ok, out, path):
    """Angles, edge lengths and Q_t of the measured rows `ok` of cloud `c`, one line a method."""
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
            ax.step(lo, cnt / total, where="post", color=COLORS.get(r["method"]), label=METHODS[r["method"]][1],
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
    return save_figure(plt, fig, path)


def scaling_plot(plt, rows, shapes, slopes, path):
    """Time against points of the generated clouds of `shapes`, log-log, with the fitted slope of each
    method (stored into `slopes`)."""
    import numpy as np
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
                ax.plot(xs, 10 ** (b + k * np.log10(xs)), color=COLORS.get(meth), linewidth=0.8, linestyle="--")
                label += " (slope %.2f)" % k
            ax.plot(ns, ts, "o", color=COLORS.get(meth), label=label, markersize=4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("input points")
        ax.set_ylabel("time [s]")
        ax.set_title(s)
        ax.legend(fontsize=7)
        ax.grid(True, which="both", linewidth=0.3)
    return save_figure(plt, fig, path)
