#include "filter_g2s.h"

#include "filter_g2s_layer.h"
#include <growth/meshlab/interrupt.h>

#include <growth/error.h>

#include <new>

FilterG2SPlugin::FilterG2SPlugin() { addFilter(FP_ROBUST_G2S, this); }

QString FilterG2SPlugin::pluginName() const { return "FilterG2S"; }

// Frozen: this string is the key of the filter in .mlx scripts.
QString FilterG2SPlugin::filterName(FilterID filter) const {
  return filter == FP_ROBUST_G2S ? QString("Surface Reconstruction: Robust G2S") : QString("Error!");
}

// Frozen: the filter's name in PyMeshLab (ms.apply_filter), after MeshLab's own reconstruction filters.
QString FilterG2SPlugin::pythonName(FilterID filter) const {
  return filter == FP_ROBUST_G2S ? QString("generate_surface_reconstruction_robust_g2s") : QString();
}

// Shown at the top of the filter's dialog and as the menu's tooltip: a few sentences, so that the
// dialog fits a screen 1000 px tall. The parameters are explained by their help texts and the docs.
QString FilterG2SPlugin::filterInfo(FilterID filter) const {
  if (filter != FP_ROBUST_G2S) return QString("Error!");
  return QString(
      "Interpolating mesh growing by the <b>Gabriel 2-simplex</b> criterion: from a seed triangle, "
      "a front of free edges grows, each edge taking the point whose smallest sphere through the "
      "edge is empty, the flattest and tightest triangles first. The vertices are the input points; "
      "<b>no normals are needed</b>. The mesh is manifold and free of self-intersections, with small "
      "holes closed. It goes to a new layer with per-face quality; the cloud is left unchanged.<br><br>"
      "<i>L. Di Angelo, P. Di Stefano, L. Giaccari</i><br>"
      "<b>\"A Fast Mesh-Growing Algorithm for Manifold Surface Reconstruction\"</b><br>"
      "Computer-Aided Design &amp; Applications 10(2), 2013, 197-220.");
}

FilterG2SPlugin::FilterClass FilterG2SPlugin::filterClass(FilterID) const { return Remeshing; }

int FilterG2SPlugin::postConditions(FilterID) const {
  return MeshModel::MM_VERTNUMBER | MeshModel::MM_FACENUMBER;
}

void FilterG2SPlugin::addParameters(FilterID filter, const MeshModel& m, RichParameterList& parlst) {
  if (filter != FP_ROBUST_G2S) return;
  const growth::g2s::Params def = growth::g2s::suggestParams(m.cm);
  parlst.addParam(RichFloat("seedSearchFactor", float(def.seedSearchFactor), "Seed search factor k",
      "A seed triangle's third point is searched within k times the length of its first edge from "
      "that edge's midpoint (paper, section 3.1)."));
  parlst.addParam(RichFloat("maxSearchRadius", float(def.maxSearchRadiusFactor), "Maximum search radius",
      "Largest search sphere radius for a front edge, in multiples of the local spacing (the mean "
      "length of the mesh edges already at the edge's two points); the search starts at the "
      "edge's length and grows in n steps up to it (paper, section 3.2). Larger values bridge "
      "sparser regions and fill more holes but may create long triangles. 0 uses the default."));
  parlst.addParam(RichInt("sizeLevels", def.sizeLevels, "Size priority levels n",
      "Number of search radii from the edge length to the maximum search radius; the radius at "
      "which a front edge finds its point is its size priority (paper, sections 3.2 and 4.1)."));
  parlst.addParam(RichInt("flatnessLevels", def.flatnessLevels, "Flatness priority levels m",
      "Number of classes of the angle (0 to 180 degrees) between the front triangle and the "
      "candidate triangle; flatter continuations are grown first, which avoids twisted surfaces "
      "near thin parts (paper, section 4.1)."));
  parlst.addParam(RichBool("removeNonManifoldVertices", def.removeNonManifoldVertices,
      "Remove non-manifold vertices",
      "Remove the triangles of the extra fans around vertices whose triangles form more than one "
      "fan (paper, section 4.2), so that the output is manifold."));
  parlst.addParam(RichInt("maxHoleEdges", def.maxHoleEdges, "Close holes up to (edges)",
      "After the paper's method, boundary loops of at most this many edges (small holes left by "
      "noise) are closed by triangles between their own points, each checked to keep the mesh "
      "manifold, consistently oriented and free of intersecting faces; a loop that cannot be closed "
      "so is left open. 0 turns the pass off (it runs only with the non-manifold removal on). Real "
      "holes of the object that small are closed too."));
  parlst.addParam(RichBool("removeSmallHandles", def.removeSmallHandles, "Cut small handles",
      "Where two sheets of the surface come within a spacing or two (a thin plate's rim, the "
      "overlapping layers of a merged scan), the growth can join them twice and leave a tunnel. A "
      "handle around three points (a cycle of three edges that bounds no face and does not "
      "separate the mesh around it) is cut: the faces on one side of the cycle are taken out and "
      "the two loops closed as by the hole pass; where they do not close, the cut is undone. "
      "Handles of the object wider than three points stay. Needs the two options above."));
  parlst.addParam(RichInt("minComponentFaces", def.minComponentFaces, "Smallest piece kept",
      "Connected pieces of the mesh with fewer faces are dropped (the largest piece always stays): "
      "triangles built among stray points and outliers, apart from the surface. 0 keeps all."));
  parlst.addParam(RichInt("randomSeed", int(def.randomSeed), "Random seed",
      "Seed of the random choice of seed points: the same seed gives the same mesh."));
}

bool FilterG2SPlugin::apply(FilterID filter, MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                            growth::meshlab::Outputs& outputs) {
  if (filter == FP_ROBUST_G2S) return applyRobustG2S(md, par, cb, outputs);
  errorMessage = "Unknown filter.";
  return false;
}

bool FilterG2SPlugin::applyRobustG2S(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                                     growth::meshlab::Outputs& outputs) {
  MeshModel* in = md.mm();
  if (in == nullptr) {
    errorMessage = "No current layer: load a point cloud first.";
    return false;
  }
  growth::g2s::Params p;
  p.seedSearchFactor = par.getFloat("seedSearchFactor");
  p.maxSearchRadiusFactor = par.getFloat("maxSearchRadius");
  p.sizeLevels = par.getInt("sizeLevels");
  p.flatnessLevels = par.getInt("flatnessLevels");
  p.removeNonManifoldVertices = par.getBool("removeNonManifoldVertices");
  p.maxHoleEdges = par.getInt("maxHoleEdges");
  p.removeSmallHandles = par.getBool("removeSmallHandles");
  p.minComponentFaces = par.getInt("minComponentFaces");
  p.randomSeed = static_cast<std::uint64_t>(par.getInt("randomSeed"));

  // The engine writes straight into the new layer (no copy of a large mesh); on any failure the
  // layer is removed again, so the document is left as it was.
  growth::g2s::Stat st;
  MeshModel* out = md.addNewMesh("", in->label() + " (robust G2S)", false);
  out->updateDataMask(MeshModel::MM_FACEQUALITY);
  QString failure;
  // Ctrl-C cancels (the hosts' own callbacks never do).
  growth::meshlab::InterruptToCancel interrupt(cb);
  try {
    growth::g2s::build(in->cm, out->cm, p, st, interrupt.callback());
    if (st.faces == 0)
      failure = QString("Robust G2S: ") + (st.warnings.empty() ? QString("no surface was built.")
                                                               : QString::fromStdString(st.warnings.front()));
  } catch (const growth::Cancelled&) {
    failure = "Robust G2S was cancelled; no layer was added.";
  } catch (const growth::Error& e) {
    failure = QString("Robust G2S: ") + e.what();
  } catch (const std::bad_alloc&) {
    failure = "Robust G2S ran out of memory.";
  } catch (const std::exception& e) {
    failure = QString("Robust G2S failed: ") + e.what();
  }
  if (!failure.isEmpty()) {
    removeLayer(md, out);
    md.setCurrentMesh(in->id());
    errorMessage = failure;
    Log(GLLogStream::WARNING, "%s", qUtf8Printable(errorMessage));
    return false;
  }
  md.setCurrentMesh(out->id()); // (build() gave it its bounding box and normals)
  // PyMeshLab's output dictionary of apply_filter.
  outputs["vertices"] = int(st.vertices);
  outputs["faces"] = int(st.faces);
  outputs["holes"] = int(st.holes);
  outputs["non_manifold_vertices_removed"] = int(st.nonManifoldVerticesRemoved);
  outputs["faces_removed"] = int(st.facesRemoved);
  outputs["self_intersection_faces_removed"] = int(st.selfIntersectionFacesRemoved);
  outputs["holes_closed"] = int(st.holesClosed);
  outputs["hole_faces_added"] = int(st.holeFacesAdded);
  outputs["hole_faces_replaced"] = int(st.holeFacesReplaced);
  outputs["hole_spikes_removed"] = int(st.holeSpikes);
  outputs["holes_regrown"] = int(st.holesRegrown);
  outputs["handles_cut"] = int(st.handlesCut);
  outputs["handles"] = int(st.handles);
  outputs["pieces_dropped"] = int(st.componentsDropped); // smaller than minComponentFaces
  outputs["seconds"] = double(st.seconds);

  for (const std::string& w : st.warnings) Log(GLLogStream::WARNING, "Robust G2S warning: %s", w.c_str());
  Log("Robust G2S: %zu points (%zu duplicates dropped), %zu dense clumps meshed as one point each (%zu points "
      "not used), mean spacing %g, maximum search radius %.2f x local spacing",
      st.inputPoints, st.duplicatesDropped, st.clumps, st.clumpPointsMerged, st.spacing, st.maxSearchRadiusFactor);
  Log("Robust G2S: %zu faces on %zu vertices (%zu points unused), %zu seeds", st.faces, st.vertices,
      st.unusedPoints, st.seeds);
  if (st.thinPartRefusals > 0)
    Log("Robust G2S: %zu candidates refused at thin parts (a fold or a crossing into the material between "
        "two close sheets; not in the paper)",
        st.thinPartRefusals);
  Log("Robust G2S: %zu boundary edges, %zu holes, %zu non-manifold vertices removed (%zu faces), "
      "%zu front edges left open at points with no room for another edge",
      st.boundaryEdges, st.holes, st.nonManifoldVerticesRemoved, st.facesRemoved, st.edgesLeftAtFullPoints);
  Log("Robust G2S: %zu faces removed that intersected others; hole pass: %zu holes closed with %zu faces "
      "(%zu faces at them replaced; %zu of the holes closed wider, taking out %zu faces, %zu of them grown "
      "into again on the points around them; %zu points left without a face: spikes, and the points of "
      "widened loops)",
      st.selfIntersectionFacesRemoved, st.holesClosed, st.holeFacesAdded, st.holeFacesReplaced, st.holesWidened,
      st.holeFacesWidened, st.holesRegrown, st.holeSpikes);
  if (p.removeNonManifoldVertices)
    Log("Robust G2S: %zu handles (genus, summed over the pieces); %zu small handles cut (%zu faces taken out, "
        "%zu added to close them)",
        st.handles, st.handlesCut, st.handleFacesRemoved, st.handleFacesAdded);
  if (st.componentsDropped > 0)
    Log("Robust G2S: %zu piece%s of fewer than %d faces dropped (%zu faces): triangles among stray points",
        st.componentsDropped, st.componentsDropped == 1 ? "" : "s", p.minComponentFaces, st.componentFacesDropped);
  for (const auto& pass : st.passes)
    Log("Robust G2S pass, %s: %zu faces out, %zu in, %.3f s", pass.name.c_str(), pass.facesRemoved, pass.facesAdded,
        pass.seconds);
  Log("Robust G2S: time %.3f s (setup %.3f, growth %.3f, clean-up %.3f, output %.3f; %.0f triangles/s)", st.seconds,
      st.secondsSetup, st.secondsGrowth, st.secondsCleanup, st.secondsOutput, st.seconds > 0 ? double(st.faces) / st.seconds : 0.0);
  return true;
}
