"""The filters in the real PyMeshLab 2025.7 wheel, loaded by `import growth_meshers`.

Run in a venv holding pymeshlab==2025.7.post1 and this package (`pip install .`), e.g. by
scripts/test_python.sh. The comparison with the MeshLab 2020.09 route needs GROWTH_BUILD_DIR (a
build with the 2020.09 plugins, build/plugins/) and Debian's meshlabserver; without them those tests
skip, unless GROWTH_REQUIRE_MESHLAB2020=1 (as in scripts/test.sh), where they fail.
"""

import os
import pathlib
import re
import shutil
import subprocess

import numpy as np
import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import pymeshlab  # noqa: E402
import growth_meshers  # noqa: E402

SP = "generate_surface_reconstruction_sphere_packing"
G2S = "generate_surface_reconstruction_robust_g2s"
REMESH = "meshing_sphere_packing_remeshing"
SOURCE = pathlib.Path(os.environ.get("GROWTH_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


# --- Clouds: seeded, float-representable coordinates (so that the float 2020.09 route reads the
# same numbers as the double one) ----------------------------------------------------------------

def sphere_cloud(n=20000, seed=1, radius=1.0):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    p = (radius * v).astype(np.float32).astype(np.float64)
    return p, v.astype(np.float32).astype(np.float64)


def torus_cloud(n=20000, seed=2, R=1.0, r=0.35):
    rng = np.random.default_rng(seed)
    u, w = rng.uniform(0, 2 * np.pi, n), rng.uniform(0, 2 * np.pi, n)
    nrm = np.stack([np.cos(u) * np.cos(w), np.sin(u) * np.cos(w), np.sin(w)], axis=1)
    c = np.stack([R * np.cos(u), R * np.sin(u), np.zeros(n)], axis=1)
    return (c + r * nrm).astype(np.float32).astype(np.float64), nrm.astype(np.float32).astype(np.float64)


def meshset_with(points, normals=None, name="cloud"):
    ms = pymeshlab.MeshSet()
    if normals is None:
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=points), name)
    else:
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=points, v_normals_matrix=normals), name)
    return ms


def edges_of(faces):
    e = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    return np.unique(e, axis=0, return_counts=True)


def assert_closed_manifold(ms):
    topo = ms.get_topological_measures()
    assert topo["is_mesh_two_manifold"], topo
    assert topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0, topo
    assert topo["boundary_edges"] == 0, topo
    assert topo["connected_components_number"] == 1, topo
    return topo


# --- Loading -------------------------------------------------------------------------------------

def test_import_loads_both_filters_and_binds_methods():
    names = pymeshlab.filter_list()
    assert SP in names and G2S in names
    assert callable(getattr(pymeshlab.MeshSet, SP)) and callable(getattr(pymeshlab.MeshSet, G2S))
    assert growth_meshers.FILTERS == (SP, G2S, REMESH)
    assert REMESH in names and callable(getattr(pymeshlab.MeshSet, REMESH))
    assert all(p.is_file() and p.parent.name == "plugins" for p in growth_meshers.PLUGINS)


def test_a_second_load_is_harmless():
    import importlib

    importlib.reload(growth_meshers)
    assert pymeshlab.filter_list().count(SP) == 1 and pymeshlab.filter_list().count(G2S) == 1


def test_plugins_bind_the_wheels_qt_and_libmeshlab_common():
    wheel_lib = pathlib.Path(pymeshlab.__file__).resolve().parent / "lib"
    maps = pathlib.Path("/proc/self/maps").read_text()
    mapped = set(re.findall(r"(/\S+\.so[.\d]*)$", maps, re.M))
    ours = {p for p in mapped if "/growth_meshers/plugins/" in p}
    assert len(ours) == 2, ours
    host = {p for p in mapped if re.search(r"/lib(Qt5\w+|meshlab-common)\.so", p)}
    assert any(p.endswith("libmeshlab-common.so") for p in host)
    foreign = {p for p in host if pathlib.Path(p).resolve().parent != wheel_lib}
    assert not foreign, f"libraries loaded from outside the wheel: {foreign}"
    # The plugins name the host libraries by soname only: no RUNPATH that could pull in others.
    readelf = shutil.which("readelf")
    if readelf:
        for plugin in growth_meshers.PLUGINS:
            dyn = subprocess.run([readelf, "-d", str(plugin)], capture_output=True, text=True, check=True).stdout
            assert "libmeshlab-common.so" in dyn and "RUNPATH" not in dyn and "RPATH" not in dyn, dyn


# --- Sphere Packing ------------------------------------------------------------------------------

SP_OUTPUTS = {"vertices", "faces", "holes", "faces_removed", "pieces_dropped", "sphere_diameter", "seconds",
              "memory_peak_bytes"}
G2S_OUTPUTS = {"vertices", "faces", "holes", "non_manifold_vertices_removed", "faces_removed", "seconds"}


def test_sphere_packing_adds_a_layer_and_leaves_the_cloud_untouched():
    p, n = sphere_cloud()
    ms = meshset_with(p, n)
    out = ms.apply_filter(SP)
    assert ms.mesh_number() == 2 and ms.current_mesh_id() == 1
    assert SP_OUTPUTS <= set(out), out
    mesh = ms.current_mesh()
    assert out["faces"] == mesh.face_number() > 0 and out["vertices"] == mesh.vertex_number()
    assert out["holes"] == 0 and out["faces_removed"] == 0 and out["seconds"] > 0
    # The engine's peak: more than the output's vertices and faces, and within its per-point budget.
    assert 24 * out["vertices"] + 12 * out["faces"] < out["memory_peak_bytes"] < 1000 * len(p)
    d = out["sphere_diameter"]
    assert 0 < d < 0.2
    # Every edge at least d (double precision here: no float rounding).
    v, f = mesh.vertex_matrix(), mesh.face_matrix()
    e, _ = edges_of(f)
    assert np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1).min() >= d * (1 - 1e-12)
    # Face quality: Q_t in (0, 1], near equilateral on average.
    assert mesh.has_face_scalar()
    q = mesh.face_scalar_array()
    assert q.shape == (mesh.face_number(),) and q.min() > 0 and q.max() <= 1 + 1e-9 and q.mean() > 0.9
    assert_closed_manifold(ms)
    cloud = ms.mesh(0)
    assert cloud.face_number() == 0 and np.array_equal(cloud.vertex_matrix(), p)
    assert np.array_equal(cloud.vertex_normal_matrix(), n)


def test_sphere_packing_lengths_as_pure_and_percentage_values():
    p, n = sphere_cloud()
    ms = meshset_with(p, n)
    out_abs = ms.apply_filter(SP, spherediameter=pymeshlab.PureValue(0.08))
    # MeshLab holds a length parameter as a float (FloatValue), also in PyMeshLab's double build.
    assert out_abs["sphere_diameter"] == float(np.float32(0.08))
    diag = ms.mesh(0).bounding_box().diagonal()
    ms.set_current_mesh(0)
    out_pct = ms.apply_filter(SP, spherediameter=pymeshlab.PercentageValue(100 * 0.08 / diag))
    assert out_pct["sphere_diameter"] == pytest.approx(0.08, rel=1e-6)
    assert out_pct["faces"] == pytest.approx(out_abs["faces"], rel=0.01) and ms.mesh_number() == 3
    # The splat size too, and the bound method with keywords.
    ms.set_current_mesh(0)
    out = ms.generate_surface_reconstruction_sphere_packing(spherediameter=pymeshlab.PureValue(0.1),
                                                            splatsize=pymeshlab.PercentageValue(2.0))
    assert out["sphere_diameter"] == pytest.approx(0.1, rel=1e-6) and out["holes"] == 0


def test_chaining_with_isotropic_remeshing_and_quality_filters():
    p, n = torus_cloud()
    ms = meshset_with(p, n)
    d = ms.apply_filter(SP)["sphere_diameter"]
    assert_closed_manifold(ms)
    # MeshLab's quality filters read the filter's face quality (Q_t).
    q = ms.get_scalar_statistics_per_face()
    assert 0 < q["min"] <= q["avg"] <= q["max"] <= 1 + 1e-9 and q["avg"] > 0.9, q
    ms.meshing_isotropic_explicit_remeshing(iterations=3, targetlen=pymeshlab.PureValue(d))
    assert ms.mesh_number() == 2 and ms.current_mesh().face_number() > 0
    ms.compute_scalar_by_aspect_ratio_per_face()
    stats = ms.get_scalar_statistics_per_face()
    assert 0 < stats["min"] <= stats["avg"] <= stats["max"], stats
    ms.compute_color_from_scalar_per_face()
    assert ms.current_mesh().has_face_color()
    topo = ms.get_topological_measures()
    assert topo["is_mesh_two_manifold"] and topo["genus"] == 1, topo
    # Robust G2S on the same cloud, then the same chain.
    ms.set_current_mesh(0)
    out = ms.generate_surface_reconstruction_robust_g2s()
    assert ms.mesh_number() == 3 and out["holes"] == 0
    assert ms.get_topological_measures()["genus"] == 1
    ms.meshing_isotropic_explicit_remeshing(iterations=2)
    assert ms.current_mesh().face_number() > 0


# --- Robust G2S ----------------------------------------------------------------------------------

# --- Remeshing: Sphere Packing --------------------------------------------------------------------

def test_remeshing_adds_a_layer_with_edges_at_least_d_and_leaves_the_input_untouched():
    ms = pymeshlab.MeshSet()
    ms.create_torus(hradius=3.0, vradius=1.0, hsubdiv=48, vsubdiv=24)  # genus 1, closed
    before_v, before_f = ms.current_mesh().vertex_matrix().copy(), ms.current_mesh().face_matrix().copy()
    out = ms.apply_filter(REMESH)
    assert ms.mesh_number() == 2 and ms.current_mesh_id() == 1
    assert {"vertices", "faces", "holes", "faces_removed", "pieces_dropped", "sphere_diameter", "seconds"} <= set(out), out
    mesh = ms.current_mesh()
    assert out["faces"] == mesh.face_number() > 0 and out["holes"] == 0 and out["faces_removed"] == 0
    assert out["pieces_dropped"] == 0
    d = out["sphere_diameter"]
    v, f = mesh.vertex_matrix(), mesh.face_matrix()
    e, _ = edges_of(f)
    assert np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1).min() >= d * (1 - 1e-12)
    assert mesh.has_face_scalar() and mesh.face_scalar_array().mean() > 0.85
    topo = assert_closed_manifold(ms)
    assert topo["genus"] == 1, topo
    assert np.array_equal(ms.mesh(0).vertex_matrix(), before_v) and np.array_equal(ms.mesh(0).face_matrix(), before_f)
    # An absolute d: about a quarter of the vertices at twice the default.
    ms.set_current_mesh(0)
    out2 = ms.apply_filter(REMESH, spherediameter=pymeshlab.PureValue(2 * d), mincomponentfaces=0)
    assert out2["sphere_diameter"] == pytest.approx(2 * d, rel=1e-6) and out2["pieces_dropped"] == 0
    assert 0.15 * out["vertices"] < out2["vertices"] < 0.35 * out["vertices"]


def test_remeshing_a_point_cloud_raises_the_filters_message():
    p, n = sphere_cloud(2000)
    ms = meshset_with(p, n)
    with pytest.raises(pymeshlab.PyMeshLabException, match="(?i)faces"):
        ms.apply_filter(REMESH)
    assert ms.mesh_number() == 1


def test_robust_g2s_adds_a_layer_of_the_input_points():
    p, _ = sphere_cloud(seed=3)
    ms = meshset_with(p)  # no normals needed
    out = ms.apply_filter(G2S, randomseed=1)
    assert G2S_OUTPUTS <= set(out), out
    mesh = ms.current_mesh()
    assert ms.mesh_number() == 2 and out["faces"] == mesh.face_number() > 0
    assert out["vertices"] == mesh.vertex_number() == p.shape[0]
    # The vertices are the input points themselves.
    assert np.array_equal(np.sort(mesh.vertex_matrix(), axis=0), np.sort(p, axis=0))
    assert mesh.has_face_scalar() and mesh.face_scalar_array().min() > 0
    assert out["holes"] == 0
    assert_closed_manifold(ms)
    assert ms.mesh(0).face_number() == 0 and np.array_equal(ms.mesh(0).vertex_matrix(), p)
    # The same seed gives the same mesh.
    ms.set_current_mesh(0)
    ms.apply_filter(G2S, randomseed=1)
    assert np.array_equal(ms.current_mesh().face_matrix(), mesh.face_matrix())


# --- Bad input -----------------------------------------------------------------------------------

def bad_clouds():
    p, n = sphere_cloud(n=2000)
    nan = p.copy()
    nan[5, 1] = np.nan
    return {
        "no normals": (SP, p, None, r"normal"),
        "NaN coordinate (Sphere Packing)": (SP, nan, n, r"NaN|not a number|finite"),
        "NaN coordinate (Robust G2S)": (G2S, nan, None, r"NaN|not a number|finite"),
        "too few points (Sphere Packing)": (SP, p[:2], n[:2], r"point"),
        "too few points (Robust G2S)": (G2S, p[:2], None, r"point"),
        "points on a line": (G2S, np.outer(np.linspace(0, 1, 500), [1.0, 2.0, 3.0]), None, r"line"),
    }


@pytest.mark.parametrize("case", list(bad_clouds()))
def test_bad_input_raises_the_filters_message_and_the_meshset_stays_usable(case):
    name, points, normals, message = bad_clouds()[case]
    ms = meshset_with(points, normals)
    before = ms.mesh(0).vertex_matrix().copy()
    with pytest.raises(pymeshlab.PyMeshLabException) as err:
        ms.apply_filter(name)
    text = str(err.value)
    assert re.search(r"(Sphere Packing|Robust G2S)", text) and re.search(message, text, re.I), text
    assert ms.mesh_number() == 1 and ms.current_mesh_id() == 0
    assert np.array_equal(ms.mesh(0).vertex_matrix(), before, equal_nan=True)
    # Still usable: a good cloud in the same MeshSet meshes.
    p, n = sphere_cloud(n=5000)
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=p, v_normals_matrix=n), "good")
    assert ms.apply_filter(name)["faces"] > 0 and ms.mesh_number() == 3


# --- The same meshes as the MeshLab 2020.09 route ------------------------------------------------

def meshlab2020():
    build = os.environ.get("GROWTH_BUILD_DIR")
    server = shutil.which("meshlabserver")
    ok = build and (pathlib.Path(build) / "plugins" / "libfilter_spherepack.so").is_file() and server
    if not ok:
        if os.environ.get("GROWTH_REQUIRE_MESHLAB2020") == "1":
            pytest.fail("GROWTH_BUILD_DIR/plugins (the 2020.09 plugins) or meshlabserver missing")
        pytest.skip("no MeshLab 2020.09 build (GROWTH_BUILD_DIR) or meshlabserver")
    return pathlib.Path(build)


def faces_2020(build, cloud, mlx, tmp):
    out = tmp / (mlx + ".ply")
    script = (f'source "{SOURCE}/scripts/meshlab_env.sh" && make_meshlab_prefix "{build}" "{tmp}/prefix" && '
              f'run_meshlabserver "{tmp}/prefix" -i "{cloud}" -o "{out}" -s "{SOURCE}/scripts/mlx/{mlx}.mlx" '
              f'>"{tmp}/{mlx}.log" 2>&1 && ply_faces "{out}"')
    r = subprocess.run(["bash", "-c", script], capture_output=True, text=True)
    assert r.returncode == 0, (tmp / f"{mlx}.log").read_text()
    return int(r.stdout.strip())


@pytest.mark.parametrize("shape", ["sphere", "torus"])
def test_same_face_counts_as_meshlab_2020(shape, tmp_path):
    build = meshlab2020()
    p, n = sphere_cloud() if shape == "sphere" else torus_cloud()
    ms = meshset_with(p, n)
    cloud = tmp_path / "cloud.ply"
    ms.save_current_mesh(str(cloud), save_vertex_normal=True, binary=True)
    for name, mlx in ((SP, "spherepack"), (G2S, "g2s")):
        ms.set_current_mesh(0)
        faces = ms.apply_filter(name)["faces"]
        old = faces_2020(build, cloud, mlx, tmp_path)
        # The clouds' coordinates are floats, so both routes read the same points; the engine
        # computes in double in both. Only the storage of the results differs (2020.09 keeps float
        # vertices), which may change a few decisions: the counts agree within 0.5 %.
        assert abs(faces - old) <= 0.005 * old, f"{name}: {faces} in PyMeshLab, {old} in MeshLab 2020.09"
