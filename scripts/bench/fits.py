"""Least-squares fits against the number of points: the log-log slope of the time, and the line of
the extra peak memory."""
from .config import RUN_ORDER, SHAPES


def fit_slope(ns, ts):
    import numpy as np
    x, y = np.log10(np.array(ns, float)), np.log10(np.array(ts, float))
    slope, icept = np.polyfit(x, y, 1)
    return slope, icept


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
