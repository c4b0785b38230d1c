"""The comparison benchmark of scripts/benchmark.py, one module a task:

  config          what is run: the methods, the clouds, the cloud groups of --clouds
  clouds          making and reading the input clouds (generated, scans, "-ml" normals)
  filter_scripts  the .mlx filter script of each method
  meshlabserver   running meshlabserver (wall clock, peak memory, load+save and no-op baselines)
  timing          in-process timing with build/plugin_time
  runners         one method on one cloud: a row (and the reruns --retime, --floors)
  measure         measuring a mesh with build/mesh_measures (and --remeasure)
  rows            the results store, results.jsonl
  fits            slopes of time and lines of memory against points
  plots           the histogram and scaling plots
  tables          the Markdown tables and sections
  report          results.md, and with --publish docs/benchmark/results.md
  cli             the command line
"""
