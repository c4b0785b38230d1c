"""In-process timing with build/plugin_time: the plugin loaded and applied as meshlabserver does,
one steady clock around applyFilter, on clouds up to --inproc-max-points."""
import os
import re
import subprocess

from .config import log
from .filter_scripts import mlx_filters


# Filter → the MeshLab plugin that holds it (for in-process timing with build/plugin_time).
PLUGIN_OF_FILTER = {
    "Surface Reconstruction: Ball Pivoting": "libfilter_clean.so",
    "Remeshing: Isotropic Explicit Remeshing": "libfilter_meshing.so",
    "Surface Reconstruction: Sphere Packing": "libfilter_spherepack.so",
    "Surface Reconstruction: Robust G2S": "libfilter_g2s.so",
}
INPROC_REPEAT = 5          # in-process timing: at most this many repeats (fastest kept) ...
INPROC_MIN_SECONDS = 3.0   # ... stopping once this much filter time was spent ...
INPROC_MIN_REPEATS = 1     # ... but not before this many (plugin_time --min-repeats; the published
                           # rows were timed with 1)


def inproc_time(ctx, script_path, input_path, work):
    """Times the one filter of `script_path` on `input_path` in process with build/plugin_time (the
    plugin loaded from the scratch prefix, as meshlabserver loads it; one steady clock around
    applyFilter; fastest of up to INPROC_REPEAT repeats). Returns (seconds, repeats) or None."""
    filters = mlx_filters(script_path)
    if len(filters) != 1:
        return None
    name = re.search(r'name="([^"]*)"', filters[0]).group(1)
    so = PLUGIN_OF_FILTER.get(name)
    tool = ctx.tool("plugin_time")
    if so is None or not os.path.exists(tool):
        return None
    plugin = os.path.join(ctx.prefix, "lib", "x86_64-linux-gnu", "meshlab", "plugins", so)
    proc = subprocess.run([tool, plugin, script_path, input_path, "--repeat", str(INPROC_REPEAT),
                           "--min-seconds", str(INPROC_MIN_SECONDS), "--min-repeats", str(INPROC_MIN_REPEATS)], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True, timeout=ctx.timeout)
    with open(os.path.join(work, "plugin_time.txt"), "w") as f:
        f.write(proc.stdout + proc.stderr[-4000:])
    if proc.returncode != 0:
        log("  plugin_time failed (%d): %s" % (proc.returncode, proc.stderr.strip()[-300:]))
        return None
    m = re.search(r"^seconds: ([0-9.eE+-]+)$", proc.stdout, flags=re.M)
    reps = re.search(r"^repeats:(.*)$", proc.stdout, flags=re.M)
    return (float(m.group(1)), [float(x) for x in reps.group(1).split()]) if m and reps else None


def apply_inproc_time(row, ctx, script_path, input_path, work, add=0.0):
    """For clouds up to --inproc-max-points: the row's time becomes the in-process time (plus `add`,
    the Ball Pivoting time a remeshing row builds on)."""
    if row["points"] > ctx.inproc_max_points:
        return
    t = inproc_time(ctx, script_path, input_path, work)
    if t is None:
        return
    row["time_in_process"], row["time_in_process_repeats"] = t[0], t[1]
    row["time"], row["time_source"] = t[0] + add, "in process"
