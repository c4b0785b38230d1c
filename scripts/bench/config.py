"""What the benchmark runs: the methods (their labels and order), the clouds (shapes, sizes, the data
folder's scans, noise levels, the "-ml" normals) and the cloud groups of --clouds; and the log line."""
import os
import re
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

METHODS = {
    # key: (label in the tables, short label in the plots)
    "bpa": ("Ball Pivoting (auto radius)", "BPA"),
    "bpa3": ("Ball Pivoting (r = 3 × spacing)", "BPA 3s"),
    "bpa_re": ("Ball Pivoting + remeshing (Re)", "BPA (Re)"),
    "spherepack": ("Sphere Packing (ours)", "Sphere Packing"),
    "spherepack25": ("Sphere Packing (ours, d = 2.5 × spacing)", "Sphere Packing d 2.5s"),
    "g2s": ("Robust G2S (ours)", "Robust G2S"),
    "cgal-afsr": ("CGAL Advancing Front (defaults)", "CGAL AFSR"),
}

# The peer that is not a MeshLab filter: CGAL's Advancing Front Surface Reconstruction with its
# defaults (radius_ratio_bound 5, beta 0.52), run by build/afsr_run (tools/cgal/afsr_run.cpp, built
# when CGAL is found). Timed by the tool itself: the reconstruction call alone (Delaunay
# triangulation included, reading and writing not), the fastest of the row's repeats.
AFSR = "cgal-afsr"
NOT_MESHLAB = (AFSR,)

# Run order within a cloud: the sphere packer first, its d is the remeshing target of "bpa_re".
RUN_ORDER = ["spherepack", "spherepack25", "g2s", "bpa", "bpa3", "bpa_re", AFSR]
TABLE_ORDER = ["bpa", "bpa3", "bpa_re", AFSR, "spherepack", "spherepack25", "g2s"]
OURS = ("spherepack", "spherepack25", "g2s")
SPHERE_PACKERS = ("spherepack", "spherepack25")
SPHEREPACK25_SPACINGS = 2.5      # "spherepack25": sphereDiameter = 2.5 × the cloud's mean spacing
REFERENCE = "bpa"
SHAPES = ["sphere", "torus", "patch"]
DATA = {
    "bunny": "bunny_merged_normals.ply",
    "hand": "hand.ply",
    "horse": "horse_mesh.ply",   # its vertices (with their normals) as a clean cloud
}

# "<cloud>-ml": the same points with their normals replaced by MeshLab's own estimate (Compute normals
# for point sets with these parameters), made through the scratch meshlabserver into OUT/clouds/.
ML_NORMALS_SUFFIX = "-ml"
ML_NORMALS_PARAMS = {"K": 10, "smoothIter": 0, "flipFlag": "false", "viewPos": (0, 0, 0)}
ML_NORMALS_TEXT = "MeshLab's Compute normals for point sets (K = 10, smoothIter 0, flipFlag false, viewPos 0,0,0)"
DATA_CLOUDS = [n for d in DATA for n in (d, d + ML_NORMALS_SUFFIX)]
QUICK_DATA_CLOUDS = ["hand", "hand" + ML_NORMALS_SUFFIX]

# Perturbed generated clouds: "<shape>-<size>-gauss<P>" has isotropic Gaussian noise of standard
# deviation P % of the clean cloud's mean spacing (Robust G2S sec. 5.2), "<shape>-<size>-out<P>" P %
# outliers on top of the surface points, uniform in the enlarged box (make_cloud --outliers).
# The group "noisy" (or "noisy-<size>", default 100k) is every one of NOISE_LEVELS on every shape of
# --shapes; "scans" is the clouds of the data folder with their own normals.
NOISE_LEVELS = ["gauss10", "gauss25", "gauss50", "out5", "out10", "out20"]
NOISY_GROUP_SIZE = 100000
FULL_SIZES = [10000, 30000, 100000, 300000, 1000000]
QUICK_SIZES = [10000, 30000]


def parse_size(text):
    t = text.strip().lower()
    mult = 1
    if t.endswith("k"):
        mult, t = 1000, t[:-1]
    elif t.endswith("m"):
        mult, t = 1000000, t[:-1]
    return int(float(t) * mult)


def size_label(n):
    if n >= 1000000 and n % 1000000 == 0:
        return "%dM" % (n // 1000000)
    if n >= 1000 and n % 1000 == 0:
        return "%dk" % (n // 1000)
    return str(n)


def expand_groups(specs, shapes):
    """The cloud groups of --clouds: "noisy" / "noisy-<size>" (every NOISE_LEVELS perturbation of every
    shape of --shapes, at NOISY_GROUP_SIZE points or <size>) and "scans" (the data folder's clouds
    with their own normals); other names stay as they are."""
    out = []
    for spec in specs:
        m = re.match(r"^noisy(?:-([0-9.]+[kKmM]?))?$", spec)
        if m:
            n = parse_size(m.group(1)) if m.group(1) else NOISY_GROUP_SIZE
            out += ["%s-%s-%s" % (s, size_label(n), p) for s in shapes for p in NOISE_LEVELS]
        elif spec == "scans":
            out += list(DATA)
        else:
            out.append(spec)
    return out


def log(msg):
    print("[benchmark %s] %s" % (time.strftime("%H:%M:%S"), msg), flush=True)
