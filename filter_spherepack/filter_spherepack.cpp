#include "filter_spherepack.h"

#include "filter_spherepack_layer.h"
#include <growth/meshlab/interrupt.h>

#include <growth/error.h>

#include <vcg/complex/append.h>
#include <vcg/complex/algorithms/update/bounding.h>
#include <vcg/complex/algorithms/update/normal.h>

#include <new>

namespace {

// Runs an engine call, turning what it throws into the filter's error text (also logged as a
// warning); `what` names the filter in the messages. False when it threw.
template <class Run, class Warn>
bool runEngine(const QString& what, QString& errorMessage, Warn&& warn, Run&& run) {
  try {
    run();
    return true;
  } catch (const growth::Cancelled&) {
    errorMessage = what + " was cancelled; no layer was added.";
    return false;
  } catch (const growth::Error& e) {
    errorMessage = what + ": " + e.what();
  } catch (const std::bad_alloc&) {
    errorMessage = what + " ran out of memory: use a larger sphere diameter d.";
  } catch (const std::exception& e) {
    errorMessage = what + " failed: " + e.what();
  }
  warn(errorMessage);
  return false;
}

// The result as a new layer named after the input, with its face quality (Q_t).
MeshModel* addResultLayer(MeshDocument& md, const MeshModel& in, const QString& suffix, CMeshO& result) {
  MeshModel* out = md.addNewMesh("", in.label() + suffix, true);
  out->updateDataMask(MeshModel::MM_FACEQUALITY);
  vcg::tri::Append<CMeshO, CMeshO>::MeshCopy(out->cm, result);
  vcg::tri::UpdateBounding<CMeshO>::Box(out->cm);
  return out;
}

} // namespace

FilterSpherePackPlugin::FilterSpherePackPlugin() {
  addFilter(FP_SPHERE_PACKING, this);
  addFilter(FP_SPHERE_PACKING_REMESH, this);
}

QString FilterSpherePackPlugin::pluginName() const { return "FilterSpherePack"; }

// Frozen: these strings are the keys of the filters in .mlx scripts.
QString FilterSpherePackPlugin::filterName(FilterID filter) const {
  switch (filter) {
  case FP_SPHERE_PACKING: return QString("Surface Reconstruction: Sphere Packing");
  case FP_SPHERE_PACKING_REMESH: return QString("Remeshing: Sphere Packing");
  default: return QString("Error!");
  }
}

// Frozen: the filters' names in PyMeshLab (ms.apply_filter), after MeshLab's own reconstruction
// (generate_surface_reconstruction_*) and remeshing (meshing_*_remeshing) filters.
QString FilterSpherePackPlugin::pythonName(FilterID filter) const {
  switch (filter) {
  case FP_SPHERE_PACKING: return QString("generate_surface_reconstruction_sphere_packing");
  case FP_SPHERE_PACKING_REMESH: return QString("meshing_sphere_packing_remeshing");
  default: return QString();
  }
}

// Shown at the top of the filter's dialog and as the menu's tooltip: a few sentences, so that the
// dialog fits a screen 1000 px tall. The parameters are explained by their help texts and the docs.
QString FilterSpherePackPlugin::filterInfo(FilterID filter) const {
  if (filter == FP_SPHERE_PACKING_REMESH)
    return QString(
        "Remeshes a triangle mesh by packing touching spheres of diameter <i>d</i> on its surface; the "
        "centres of the spheres become the vertices, all on the input surface. Every edge is at least "
        "<i>d</i> long, the triangles are close to equilateral, the mesh is manifold without "
        "intersecting faces, and it keeps the input's components, borders and genus where <i>d</i> is "
        "below the size of its features. <i>d</i> left at 0 is the input's mean edge length. The mesh "
        "goes to a new layer with per-face quality; the input is left unchanged.<br><br>"
        "<i>H. Lipsch&uuml;tz, U. Reitebuch, K. Polthier, M. Skrodzki</i><br>"
        "<b>\"Manifold Meshing of Point Clouds with Guaranteed Smallest Edge Length\"</b>, sections 3, 4 "
        "and 6.");
  if (filter != FP_SPHERE_PACKING) return QString("Error!");
  return QString(
      "Reconstructs a triangle mesh from a point cloud <b>with normals</b> by packing touching "
      "spheres of diameter <i>d</i> on small disks (splats) around the points; the centres of the "
      "spheres become the vertices. Every edge is at least <i>d</i> long, the triangles are close to "
      "equilateral and the mesh is manifold. Lengths left at 0 are chosen from the cloud. The mesh "
      "goes to a new layer with per-face quality; the cloud is left unchanged.<br>"
      "Needs per-vertex normals: <i>Filters &gt; Normals, Curvatures and Orientation &gt; Compute "
      "normals for point sets</i>.<br><br>"
      "<i>H. Lipsch&uuml;tz, U. Reitebuch, K. Polthier, M. Skrodzki</i><br>"
      "<b>\"Manifold Meshing of Point Clouds with Guaranteed Smallest Edge Length\"</b>, sections 3 "
      "and 4.");
}

FilterSpherePackPlugin::FilterClass FilterSpherePackPlugin::filterClass(FilterID) const { return Remeshing; }

int FilterSpherePackPlugin::preConditions(FilterID filter) const {
  return filter == FP_SPHERE_PACKING_REMESH ? int(MeshModel::MM_FACENUMBER) : int(MeshModel::MM_VERTNORMAL);
}

int FilterSpherePackPlugin::postConditions(FilterID) const {
  return MeshModel::MM_VERTNUMBER | MeshModel::MM_FACENUMBER;
}

void FilterSpherePackPlugin::addParameters(FilterID filter, const MeshModel& m, RichParameterList& parlst) {
  using growth::meshlab::RichLength;
  using growth::meshlab::RichPoint;
  if (filter == FP_SPHERE_PACKING_REMESH) {
    const growth::spherepack::RemeshParams def;
    const double autoD = growth::spherepack::defaultRemeshDiameter(m.cm);
    const float diag = m.cm.bbox.IsNull() ? 1.0f : m.cm.bbox.Diag();
    const QString autoText = autoD > 0 ? QString(" For this layer: %1.").arg(autoD) : QString();
    parlst.addParam(RichLength("sphereDiameter", 0.0f, 0.0f, diag,
        "Sphere diameter d (shortest edge)",
        "Every edge is at least d; most are close to it. 0 = the mean edge length." + autoText));
    parlst.addParam(RichInt("windowSize", def.windowSize, "Window size w",
        "Border window of the candidate priorities (sec. 4.2); 0 = breadth-first."));
    parlst.addParam(RichInt("maxBorderLength", def.maxBorderLength, "Border limit",
        "Regions with a longer border (in edges) stay open as holes (sec. 3.7)."));
    parlst.addParam(RichFloat("creaseAngle", float(def.creaseAngleDeg), "Crease angle (degrees)",
        "Edges whose faces' normals differ by more than this are creases."));
    parlst.addParam(RichInt("minComponentFaces", def.minPieceFaces, "Smallest piece kept (faces)",
        "Pieces of the output with fewer faces are dropped, but every connected part of the input keeps its "
        "largest piece. 0 keeps all."));
    return;
  }
  if (filter != FP_SPHERE_PACKING) return;
  // Lengths default to 0 = automatic (like Ball Pivoting's radius): derived from each cloud when
  // the filter runs, so the same .mlx script suits clouds of any scale. The tooltips show what
  // "automatic" gives for the current layer.
  const growth::spherepack::Params def = growth::spherepack::suggestParams(m.cm);
  const float diag = m.cm.bbox.IsNull() ? 1.0f : m.cm.bbox.Diag();
  const QString autoD = def.sphereDiameter > 0 ? QString(" For this layer: %1.").arg(def.sphereDiameter) : QString();
  const QString autoS = def.splatSize > 0 ? QString(" For this layer: %1.").arg(def.splatSize) : QString();
  // The help texts stay short (at most 100 characters with the value for the layer) so MeshLab
  // 2020.09's dialog shows them whole; the details are in filterInfo().
  parlst.addParam(RichLength("sphereDiameter", 0.0f, 0.0f, diag,
      "Sphere diameter d (target edge length)",
      "Every edge is at least d; most are close to it. 0 = automatic." + autoD));
  parlst.addParam(RichLength("splatSize", 0.0f, 0.0f, diag,
      "Splat radius s",
      "Largest radius of the disks on the points. 0 = automatic." + autoS));
  parlst.addParam(RichBool("localSplatSizes", def.localSplatSizes, "Local splat sizes",
      "A splat radius per point, from its tangent-plane Voronoi cell (sec. 4.3)."));
  parlst.addParam(RichInt("windowSize", def.windowSize, "Window size w",
      "Border window of the candidate priorities (sec. 4.2); 0 = breadth-first."));
  parlst.addParam(RichInt("maxBorderLength", def.maxBorderLength, "Border limit",
      "Longer region borders (edges) stay open unless the cloud covers them (sec. 3.7)."));
  parlst.addParam(RichInt("minComponentFaces", def.minComponentFaces, "Smallest piece kept",
      "Pieces with fewer faces are dropped (second scan layers, stray points); 0 keeps all."));
  parlst.addParam(RichBool("useStartPoints", def.useStartPoints, "Use given starting points",
      "Start the growth from the two points below, not near the highest point."));
  parlst.addParam(RichPoint("startPoint1", Point3m(def.startPoint[0][0], def.startPoint[0][1], def.startPoint[0][2]), "Starting point 1",
      "First start point (used only with 'Use given starting points')."));
  parlst.addParam(RichPoint("startPoint2", Point3m(def.startPoint[1][0], def.startPoint[1][1], def.startPoint[1][2]), "Starting point 2",
      "Second start point, between d and 2d from the first."));
  parlst.addParam(RichBool("keepFeatures", def.keepFeatures, "Keep features",
      "Detect creases and corners in the cloud; vertices on them first, no face across a crease."));
  parlst.addParam(RichFloat("creaseAngle", float(def.creaseAngleDeg), "Crease angle (degrees)",
      "With 'Keep features': surfaces meeting at more than this angle form a crease."));
}

bool FilterSpherePackPlugin::apply(FilterID filter, MeshDocument& md, const RichParameterList& par,
                                   vcg::CallBackPos* cb, growth::meshlab::Outputs& outputs) {
  if (filter == FP_SPHERE_PACKING) return applySpherePacking(md, par, cb, outputs);
  if (filter == FP_SPHERE_PACKING_REMESH) return applyRemesh(md, par, cb, outputs);
  errorMessage = "Unknown filter.";
  return false;
}

bool FilterSpherePackPlugin::applySpherePacking(MeshDocument& md, const RichParameterList& par,
                                                vcg::CallBackPos* cb, growth::meshlab::Outputs& outputs) {
  MeshModel* in = md.mm();
  if (in == nullptr) {
    errorMessage = "No current layer: load a point cloud first.";
    return false;
  }
  growth::spherepack::Params p;
  p.sphereDiameter = par.getAbsPerc("sphereDiameter");
  p.splatSize = par.getAbsPerc("splatSize");
  p.localSplatSizes = par.getBool("localSplatSizes");
  p.windowSize = par.getInt("windowSize");
  p.maxBorderLength = par.getInt("maxBorderLength");
  p.minComponentFaces = par.getInt("minComponentFaces");
  p.useStartPoints = par.getBool("useStartPoints");
  p.startPoint[0] = growth::Vec3d::Construct(par.getPoint3m("startPoint1"));
  p.startPoint[1] = growth::Vec3d::Construct(par.getPoint3m("startPoint2"));
  p.keepFeatures = par.getBool("keepFeatures");
  p.creaseAngleDeg = par.getFloat("creaseAngle");

  growth::spherepack::Stat st;
  CMeshO result;
  // Ctrl-C cancels (the hosts' own callbacks never do).
  growth::meshlab::InterruptToCancel interrupt(cb);
  const auto warn = [this](const QString& m) { Log(GLLogStream::WARNING, "%s", qUtf8Printable(m)); };
  if (!runEngine("Sphere Packing", errorMessage, warn,
                 [&] { growth::spherepack::build(in->cm, result, p, st, interrupt.callback()); }))
    return false;
  addResultLayer(md, *in, " (sphere packing)", result);
  // PyMeshLab's output dictionary of apply_filter.
  outputs["vertices"] = int(st.vertices);
  outputs["faces"] = int(st.faces);
  outputs["holes"] = int(st.boundaryLoops);
  outputs["faces_removed"] = int(st.facesRemoved); // for a manifold mesh without intersections
  outputs["pieces_dropped"] = int(st.componentsDropped); // smaller than minComponentFaces
  outputs["sphere_diameter"] = double(st.sphereDiameter);
  outputs["seconds"] = double(st.seconds);
  outputs["memory_peak_bytes"] = double(st.memory.peak); // the engine's own arrays, at their largest sum
  if (p.keepFeatures) {
    outputs["feature_lines"] = int(st.featureLines);
    outputs["feature_corners"] = int(st.featureCorners);
  }

  for (const std::string& w : st.warnings) Log(GLLogStream::WARNING, "Sphere Packing warning: %s", w.c_str());
  Log("Sphere Packing: %zu points (%zu duplicates dropped); spacing %g (robust mean, as Robust G2S and the "
      "measures report it), median spacing %g, sqrt(area per point) %g, estimated noise %g", st.inputPoints,
      st.duplicatesDropped, st.scale.spacing, st.scale.medianSpacing, st.scale.areaSpacing, st.scale.noise);
  if (st.farPointsLeftOut > 0)
    Log("Sphere Packing: %zu far point%s left out, %g or more from the bulk of the cloud (beyond the box grid's "
        "reach at this d)", st.farPointsLeftOut, st.farPointsLeftOut == 1 ? "" : "s", st.farPointsGap);
  else
    Log("Sphere Packing: no far points left out");
  Log("Sphere Packing: sphere diameter d = %g, s = %g%s (mean splat radius %g); d %s", st.sphereDiameter, st.splatSize,
      p.localSplatSizes ? " with local splat sizes" : "", st.meanSplatRadius, st.diameterReason.c_str());
  Log("Sphere Packing: %zu component%s started, %zu points left with no vertex within d (%zu of them where a "
      "vertex within 2d kept a new start off: a second layer of a surface already meshed)", st.componentsStarted,
      st.componentsStarted == 1 ? "" : "s", st.unreachedPoints, st.startsRefusedNearMesh);
  Log("Sphere Packing: %zu piece%s with fewer than %d faces dropped (%zu faces): flaps on misregistered scan "
      "layers, bits of stray points", st.componentsDropped, st.componentsDropped == 1 ? "" : "s",
      p.minComponentFaces, st.componentFacesDropped);
  Log("Sphere Packing: %zu vertices, %zu faces, smallest edge %g (as stored), Q_avg %.4f; %zu holes (boundary "
      "loops; before the hole pass: %zu regions left open by the border limit or not triangulable, %zu faces removed "
      "for a manifold mesh without intersections, %zu faces with (nearly) collinear vertices left out); %zu of %zu "
      "boxes where d looked too large (%zu of them saw two sides and kept both, as two layers)",
      st.vertices, st.faces, st.smallestEdge, st.qualityAvg, st.boundaryLoops, st.regionsLeftOpen, st.facesRemoved,
      st.flatFacesRemoved, st.boxesDTooLarge, st.boxes, st.boxesTwoSided);
  Log("Sphere Packing: hole pass: %zu holes closed where the cloud covers them (%zu faces added, %zu taken out "
      "around them); left open: %zu not covered by the cloud (a real boundary), %zu too long, %zu not "
      "triangulable, %zu folded, %zu through the mesh, %zu other",
      st.holesClosed, st.holeFacesAdded, st.holeFacesRemoved, st.holesNotCovered, st.holesTooLong,
      st.holesNotTriangulable, st.holesFolded, st.holesCrossing, st.holesOther);
  if (p.keepFeatures)
    Log("Sphere Packing: keep features (crease angle %g degrees): %zu crease points, %zu crease lines, %zu corners, "
        "%zu vertices placed on them first, %zu sides", p.creaseAngleDeg, st.featureCreasePoints, st.featureLines,
        st.featureCorners, st.featureVertices, st.featurePatches);
  Log("Sphere Packing: %zu candidates, %zu re-queued, rejected: %zu too close, %zu crossing, %zu twisted",
      st.candidates, st.requeued, st.rejectedTooClose, st.rejectedCrossing, st.rejectedInconsistent);
  Log("Sphere Packing: time %.3f s (input %.3f, splats %.3f, box grid %.3f, growth %.3f, regions %.3f, clean-up %.3f, "
      "output %.3f)", st.seconds, st.secondsInput, st.secondsSplats, st.secondsBoxGrid, st.secondsGrowth,
      st.secondsTriangulation, st.secondsCleanup, st.secondsOutput);
  const double mib = 1.0 / (1024.0 * 1024.0);
  Log("Sphere Packing: memory peak %.1f MiB, %.0f bytes per point (input %.1f, box grid %.1f, growth %.1f, faces "
      "%.1f, output %.1f MiB); estimated beforehand %.1f MiB, against %.1f MiB available", mib * double(st.memory.peak),
      double(st.memory.peak) / double(std::max<size_t>(st.inputPoints, 1)), mib * double(st.memory.input),
      mib * double(st.memory.boxGrid), mib * double(st.memory.growth), mib * double(st.memory.faces),
      mib * double(st.memory.output), mib * double(st.memory.estimate), mib * double(st.memory.limit));
  return true;
}

bool FilterSpherePackPlugin::applyRemesh(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                                         growth::meshlab::Outputs& outputs) {
  MeshModel* in = md.mm();
  if (in == nullptr) {
    errorMessage = "No current layer: load a triangle mesh first.";
    return false;
  }
  growth::spherepack::RemeshParams p;
  p.sphereDiameter = par.getAbsPerc("sphereDiameter");
  p.windowSize = par.getInt("windowSize");
  p.maxBorderLength = par.getInt("maxBorderLength");
  p.creaseAngleDeg = par.getFloat("creaseAngle");
  p.minPieceFaces = par.getInt("minComponentFaces");

  growth::spherepack::RemeshStat st;
  CMeshO result;
  growth::meshlab::InterruptToCancel interrupt(cb);
  const auto warn = [this](const QString& m) { Log(GLLogStream::WARNING, "%s", qUtf8Printable(m)); };
  if (!runEngine("Sphere Packing remeshing", errorMessage, warn,
                 [&] { growth::spherepack::remesh(in->cm, result, p, st, interrupt.callback()); }))
    return false;
  addResultLayer(md, *in, " (sphere packing remesh)", result);
  outputs["vertices"] = int(st.vertices);
  outputs["faces"] = int(st.faces);
  outputs["holes"] = int(st.boundaryLoops);
  outputs["faces_removed"] = int(st.facesRemoved);
  outputs["pieces_dropped"] = int(st.piecesDropped); // smaller than minComponentFaces
  outputs["sphere_diameter"] = double(st.sphereDiameter);
  outputs["seconds"] = double(st.seconds);

  for (const std::string& w : st.warnings) Log(GLLogStream::WARNING, "Sphere Packing remesh warning: %s", w.c_str());
  Log("Sphere Packing remesh: input %zu vertices, %zu faces, %zu component%s, %zu boundary edges, mean edge %g, "
      "area %g", st.inputVertices, st.inputFaces, st.inputComponents, st.inputComponents == 1 ? "" : "s",
      st.inputBoundaryEdges, st.inputMeanEdge, st.inputArea);
  Log("Sphere Packing remesh: sphere diameter d = %g (%s); %zu growth%s started, %zu input faces with no vertex "
      "within d", st.sphereDiameter, st.diameterReason.c_str(), st.componentsStarted,
      st.componentsStarted == 1 ? "" : "s", st.unreachedFaces);
  Log("Sphere Packing remesh: %zu vertices, %zu faces, smallest edge %g (as stored), Q_avg %.4f; %zu boundary "
      "loops (%zu regions left open, %zu of them beyond the input's boundary; %zu faces removed for a manifold "
      "mesh without intersections; %zu holes closed by the hole pass with %zu faces)", st.vertices, st.faces,
      st.smallestEdge, st.qualityAvg, st.boundaryLoops, st.holes, st.regionsOutside, st.facesRemoved,
      st.holesClosed, st.holeFacesAdded);
  Log("Sphere Packing remesh: %zu piece%s with fewer than %d faces dropped (%zu faces), the largest piece of "
      "every part of the input kept", st.piecesDropped, st.piecesDropped == 1 ? "" : "s", p.minPieceFaces,
      st.pieceFacesDropped);
  Log("Sphere Packing remesh: %zu candidates, %zu re-queued, rejected: %zu too close, %zu crossing, %zu twisted",
      st.candidates, st.requeued, st.rejectedTooClose, st.rejectedCrossing, st.rejectedInconsistent);
  Log("Sphere Packing remesh: time %.3f s (input %.3f, growth %.3f, regions %.3f, clean-up %.3f, output %.3f)",
      st.seconds, st.secondsInput, st.secondsGrowth, st.secondsTriangulation, st.secondsCleanup, st.secondsOutput);
  return true;
}
