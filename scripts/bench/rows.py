"""The results store, OUT/results.jsonl: one JSON row per (cloud, method), merged across
invocations; and looking rows up."""
import json
import os

from .config import ML_NORMALS_SUFFIX, SHAPES


def load_rows(path):
    rows = []
    if os.path.exists(path):
        for line in open(path):
            line = line.strip()
            if line:
                rows.append(json.loads(line))
    return rows


def save_rows(path, rows):
    with open(path + ".tmp", "w") as f:
        for r in rows:
            f.write(json.dumps(r, sort_keys=True) + "\n")
    os.replace(path + ".tmp", path)


def merge_row(rows, row):
    rows = [r for r in rows if not (r["cloud"] == row["cloud"] and r["method"] == row["method"])]
    rows.append(row)
    return rows


def ok_row(rows, cloud, method):
    return next((r for r in rows if r["cloud"] == cloud and r["method"] == method and r.get("status") == "ok"), None)


def row_normals(r):
    """"own" or "meshlab" (rows from before the normals were recorded: from the cloud's name)."""
    return r.get("normals") or ("meshlab" if r["cloud"].endswith(ML_NORMALS_SUFFIX) else "own")


def cloud_sort_key(name, rows):
    r = next(x for x in rows if x["cloud"] == name)
    kind_order = {"generated": 0, "data": 1, "file": 2}
    # A perturbed generated cloud (no shape of its own) sorts with its shape's clean clouds.
    shape = r.get("shape") or (name.split("-")[0] if r.get("cloud_kind") == "generated" else "")
    return (kind_order.get(r.get("cloud_kind"), 3), SHAPES.index(shape) if shape in SHAPES else 9, r["points"], name)


def sorted_clouds(rows):
    """The clouds of the rows, generated ones first (by shape and size), then the scans, then files."""
    return sorted({r["cloud"] for r in rows}, key=lambda n: cloud_sort_key(n, rows))
