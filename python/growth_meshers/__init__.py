"""Sphere Packing and Robust G2S surface reconstruction, and Sphere Packing remeshing, for PyMeshLab 2025.7.

Importing this package loads its two MeshLab filter plugins into PyMeshLab, so that

    import pymeshlab
    import growth_meshers
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh("cloud.ply")
    ms.generate_surface_reconstruction_sphere_packing()   # needs normals
    ms.generate_surface_reconstruction_robust_g2s()
    ms.meshing_sphere_packing_remeshing()                 # on a triangle mesh

work like PyMeshLab's own filters (also through ``ms.apply_filter(name, ...)``).
"""

import pathlib

import pymeshlab

__all__ = ["FILTERS", "PLUGINS", "__version__"]

try:
    from importlib.metadata import version as _version

    __version__ = _version("growth-meshers")
except Exception:  # not installed as a distribution (e.g. run from a build tree)
    __version__ = "unknown"

_here = pathlib.Path(__file__).resolve().parent

#: The plugin libraries this package loads, built for PyMeshLab 2025.7 (double precision).
PLUGINS = (_here / "plugins" / "libfilter_spherepack.so", _here / "plugins" / "libfilter_g2s.so")

#: The filters' PyMeshLab names: each plugin's first filter (in the order of PLUGINS), then the others.
FILTERS = ("generate_surface_reconstruction_sphere_packing", "generate_surface_reconstruction_robust_g2s",
           "meshing_sphere_packing_remeshing")


def _load():
    loaded = set(pymeshlab.filter_list())
    for plugin, name in zip(PLUGINS, FILTERS[: len(PLUGINS)]):
        if name in loaded:  # a second import, or another copy of the plugin already loaded
            continue
        if not plugin.is_file():
            raise ImportError(f"growth_meshers: the plugin {plugin} is missing; reinstall the package")
        try:
            pymeshlab.load_plugin(str(plugin))
        except pymeshlab.PyMeshLabException as e:
            raise ImportError(
                f"growth_meshers: PyMeshLab refused {plugin.name}: {e}. "
                "The plugins are built for pymeshlab 2025.7 (pip install pymeshlab==2025.7.post1)."
            ) from e
    # PyMeshLab binds each filter as a MeshSet method when it is imported; bind ours the same way.
    for name in FILTERS:
        if not hasattr(pymeshlab.MeshSet, name):
            setattr(pymeshlab.MeshSet, name, pymeshlab.bind_function(name))


_load()
