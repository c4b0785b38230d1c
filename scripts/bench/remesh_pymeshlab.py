"""One remeshing run in PyMeshLab 2025.7, in a process of its own (so that its peak memory is the
method's): MeshLab's Isotropic Explicit Remeshing or our Sphere Packing remeshing filter, applied to
a mesh at an absolute target length L, the output saved as binary PLY. Prints one JSON object.

    python remesh_pymeshlab.py ier  IN.ply OUT.ply L [--iterations 3]
    python remesh_pymeshlab.py ours IN.ply OUT.ply L [--plugin LIB.so] [--filter NAME]

ier:  meshing_isotropic_explicit_remeshing(iterations=3, targetlen=pymeshlab.PureValue(L)), every
      other parameter at its default (featuredeg 30, checksurfdist with maxsurfdist 1 % of the
      bounding box diagonal, reprojection on).
ours: the filter NAME (default meshing_sphere_packing_remeshing) of our plugin, loaded from LIB.so
      with pymeshlab.load_plugin, or by `import growth_meshers` (the installed package) without
      --plugin; its parameter whose name holds "diameter" (the sphere diameter d) set to
      PureValue(L), the others at their defaults. When the plugin has no such filter the run prints
      {"status": "skipped: ..."} and exits 0.

Reported: "seconds", the wall time of the filter call alone (time.perf_counter); "load_rss_mib",
the process's peak resident set size once PyMeshLab is imported and the mesh loaded;
"peak_rss_mib", its peak after the filter (getrusage; the process runs nothing else).
"""
import argparse
import importlib.metadata
import json
import os
import resource
import sys
import time

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pymeshlab  # noqa: E402

OUR_FILTER = "meshing_sphere_packing_remeshing"


def peak_rss_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("method", choices=["ier", "ours"])
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("target", type=float, help="target edge length L (absolute)")
    ap.add_argument("--iterations", type=int, default=3)
    ap.add_argument("--plugin", help="our plugin library (libfilter_spherepack.so built for PyMeshLab 2025.7)")
    ap.add_argument("--filter", default=OUR_FILTER, help="our filter's PyMeshLab name")
    a = ap.parse_args()
    result = {"method": a.method, "target": a.target, "pymeshlab": importlib.metadata.version("pymeshlab")}

    if a.method == "ours":
        try:
            if a.plugin:
                pymeshlab.load_plugin(a.plugin)
                result["plugin"] = a.plugin
            else:
                import growth_meshers
                result["plugin"] = str(growth_meshers.PLUGINS[0])
        except Exception as e:  # no plugin: the row says why
            print(json.dumps(dict(result, status="skipped: our plugin could not be loaded (%s)" % e)))
            return 0
        if a.filter not in pymeshlab.filter_list():
            print(json.dumps(dict(result, status="skipped: %s has no filter %s" % (result["plugin"], a.filter))))
            return 0

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(a.input)
    result["input_faces"] = ms.current_mesh().face_number()
    result["load_rss_mib"] = peak_rss_mib()
    if a.method == "ier":
        name = "meshing_isotropic_explicit_remeshing"
        params = {"iterations": a.iterations, "targetlen": pymeshlab.PureValue(a.target)}
    else:
        name = a.filter
        keys = [k for k in ms.filter_parameter_values(name) if "diameter" in k.lower()]
        params = {keys[0]: pymeshlab.PureValue(a.target)} if keys else {}
        result["parameters"] = {k: a.target for k in params}
    layers = ms.mesh_number()
    t0 = time.perf_counter()
    try:
        ms.apply_filter(name, **params)
    except pymeshlab.PyMeshLabException as e:
        print(json.dumps(dict(result, status="failed: %s" % e)))
        return 0
    result["seconds"] = time.perf_counter() - t0
    result["peak_rss_mib"] = peak_rss_mib()
    # IER changes the current layer; a filter that adds a layer makes it current.
    result["new_layer"] = ms.mesh_number() > layers
    ms.save_current_mesh(a.output, binary=True, save_vertex_color=False, save_vertex_quality=False,
                         save_face_quality=False, save_face_color=False, save_vertex_normal=False)
    result["faces"] = ms.current_mesh().face_number()
    result["status"] = "ok"
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
