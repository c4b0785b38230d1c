"""The MeshLab filter scripts (.mlx) of each method: the templates of scripts/mlx/ with the
parameters a method sets, MeshLab's remeshing, and the no-op filter."""
import os
import re

from .config import ROOT, SPHEREPACK25_SPACINGS


def mlx_filters(path):
    """The <filter>…</filter> blocks of an .mlx file."""
    text = open(path).read()
    return re.findall(r"<filter\b[^>]*/>|<filter\b[^>]*[^/]>.*?</filter>", text, flags=re.S)


def set_param(filter_xml, name, value):
    pat = re.compile(r'(<Param\b[^>]*\bname="%s"[^>]*>)' % re.escape(name))
    m = pat.search(filter_xml)
    if not m:
        raise SystemExit("parameter %s not found in the filter script" % name)
    tag = re.sub(r'\bvalue="[^"]*"', 'value="%s"' % value, m.group(1))
    return filter_xml[:m.start()] + tag + filter_xml[m.end():]


def set_abs_perc(filter_xml, name, value, diagonal):
    """A RichAbsPerc parameter with an absolute value (and a max that admits it)."""
    x = set_param(filter_xml, name, "%.9g" % value)
    pat = re.compile(r'(<Param\b[^>]*\bname="%s"[^>]*>)' % re.escape(name))
    m = pat.search(x)
    tag = re.sub(r'\bmax="[^"]*"', 'max="%.9g"' % max(diagonal, value), m.group(1))
    return x[:m.start()] + tag + x[m.end():]


def mlx(filters):
    return "<!DOCTYPE FilterScript>\n<FilterScript>\n " + "\n ".join(filters) + "\n</FilterScript>\n"


def remesh_filter(target, diagonal):
    """MeshLab's Isotropic Explicit Remeshing as in the paper's "(Re)" rows: 3 iterations, target
    edge length d in absolute units, MeshLab's defaults otherwise (surface distance check on with
    1 % of the diagonal, crease angle 30°, all steps on)."""
    return ('<filter name="Remeshing: Isotropic Explicit Remeshing">\n'
            '  <Param name="Iterations" type="RichInt" value="3"/>\n'
            '  <Param name="Adaptive" type="RichBool" value="false"/>\n'
            '  <Param name="SelectedOnly" type="RichBool" value="false"/>\n'
            '  <Param name="TargetLen" type="RichAbsPerc" value="%.9g" min="0" max="%.9g"/>\n'
            '  <Param name="FeatureDeg" type="RichFloat" value="30"/>\n'
            '  <Param name="CheckSurfDist" type="RichBool" value="true"/>\n'
            '  <Param name="MaxSurfDist" type="RichAbsPerc" value="%.9g" min="0" max="%.9g"/>\n'
            '  <Param name="SplitFlag" type="RichBool" value="true"/>\n'
            '  <Param name="CollapseFlag" type="RichBool" value="true"/>\n'
            '  <Param name="SwapFlag" type="RichBool" value="true"/>\n'
            '  <Param name="SmoothFlag" type="RichBool" value="true"/>\n'
            '  <Param name="ReprojectFlag" type="RichBool" value="true"/>\n'
            ' </filter>') % (target, max(diagonal, target), 0.01 * diagonal, diagonal)


def method_script(method, cloud, ctx, d_info):
    mlx_dir = os.path.join(ROOT, "scripts", "mlx")
    diag = cloud["diagonal"]
    if method in ("bpa", "bpa3", "bpa_re"):
        (f,) = mlx_filters(os.path.join(mlx_dir, "ball_pivoting.mlx"))
        info = {}
        if method == "bpa3":
            r = 3.0 * cloud["spacing"]
            f = set_abs_perc(f, "BallRadius", r, diag)
            info["ball_radius"] = r
        filters = [f]
        if method == "bpa_re":
            filters.append(remesh_filter(d_info["d"], diag))
            info["remesh_target"] = d_info["d"]
            info["remesh_target_source"] = d_info["source"]
        return mlx(filters), info
    template = {"spherepack": "spherepack.mlx", "spherepack25": "spherepack.mlx", "g2s": "g2s.mlx"}[method]
    filters = mlx_filters(os.path.join(mlx_dir, template))
    info = {}
    if method == "spherepack25":
        d = SPHEREPACK25_SPACINGS * cloud["spacing"]
        filters = [set_abs_perc(f, "sphereDiameter", d, diag) for f in filters]
        info["sphere_diameter_set"] = d
    # --param spherepack:... applies to both sphere packer methods (spherepack25:... to that one only).
    params = ctx.params.get(method, [])
    if method == "spherepack25":
        params = ctx.params.get("spherepack", []) + params
    for key, value in params:
        filters = [set_param(f, key, value) for f in filters]
    info["params"] = dict(params)
    return mlx(filters), info


# A filter that does nothing to a cloud: its run's peak is MeshLab's floor for applying any filter.
NOOP_MLX = """<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Select None">
  <Param type="RichBool" value="true" name="allFaces" description="" tooltip=""/>
  <Param type="RichBool" value="true" name="allVerts" description="" tooltip=""/>
 </filter>
</FilterScript>
"""
