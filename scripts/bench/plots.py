"""The plots: per cloud, the histograms of angles, edge lengths and Q_t of every method; time
against points (log-log, fitted slope)."""
import os

from .config import AFSR, METHODS, RUN_ORDER, SHAPES
from .fits import fit_slope
from .rows import cloud_sort_key


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
