#!/usr/bin/python3
"""The comparison benchmark: our two meshers against MeshLab's Ball Pivoting, in the same run.

Called by scripts/benchmark.sh (which builds the project and makes the scratch MeshLab prefix); see
there for the usage. For every cloud and method it runs meshlabserver once (plus one load+save-only
run of the cloud, the baseline), measures the mesh with build/mesh_measures, and writes

  OUT/results.jsonl                 one JSON row per (cloud, method), merged across invocations
  OUT/results.md                    the Markdown tables (one per cloud) and the plots
  OUT/plots/<cloud>_histograms.png  angles, edge lengths, Q_t per method (sphere-packing fig. 12)
  OUT/plots/scaling.png             time against points, log-log, fitted slope per method
  OUT/runs/<cloud>/<method>/        the .mlx, meshlabserver's log, /usr/bin/time's report,
                                    the mesh, its measures (JSON) and histograms (CSV)
  OUT/clouds/                       the generated clouds, horse's vertices, and the "-ml" clouds

Methods: Ball Pivoting with auto radius ("bpa"), with r = 3 × the mean spacing ("bpa3"), bpa's mesh
remeshed ("bpa_re"); the sphere packer at its default d ("spherepack") and at d = 2.5 × the mean
spacing ("spherepack25"); Robust G2S ("g2s"); and, not through meshlabserver, CGAL's Advancing Front
Surface Reconstruction with its defaults ("cgal-afsr", build/afsr_run, built when CGAL is found). Clouds: generated (sphere-10k, torus-1M, ...), the
scans of the data folder (bunny, hand, horse), generated ones with Gaussian noise or outliers
(sphere-100k-gauss25, torus-50k-out10; the groups "noisy" and "noisy-<size>"), .ply paths, and any of those but a path with "-ml"
appended (hand-ml, sphere-10k-ml): the same points with MeshLab's own normals (Compute normals for
point sets, K = 10, no smoothing, no flip), made by the scratch meshlabserver into OUT/clouds/.

Time: on clouds up to --inproc-max-points (100k by default), every filter, ours and MeshLab's, is
timed in process by build/plugin_time: the plugin loaded and applied as meshlabserver does, one steady
clock around applyFilter, the fastest of up to 5 repeats. Above that, our filters report their own
time in the log ("... time X s"), and MeshLab's are timed as the wall clock of the run minus the wall
clock of the load+save-only run of the same cloud (0.01 s resolution: small beside their times there).
Memory: peak resident set size of meshlabserver (/usr/bin/time -v) minus that of the
load+save-only run, per input point: the filter's extra peak. Also minus that of a run applying a
filter that does nothing (MeshLab's "Select None"): MeshLab's own cost of applying any filter, about
5 MB, which no filter can avoid and which dominates on small clouds; and, per shape, the fitted
per-point slope of the extra peak over the generated clouds' sizes.
Needs numpy and matplotlib from Debian (/usr/bin/python3), installed by scripts/setup.sh.
"""
# The code is the package scripts/bench/, one module a task (see its __init__.py); this file is its
# entry point, and its docstring is the --help text.
from bench.cli import main

if __name__ == "__main__":
    main(__doc__)
