#pragma once
// MeshLab glue of the sphere-packing mesher: parameters, reading the layer, calling the engine
// (sphere_packer.h), writing the result into a new layer, logging. No algorithm lives here.
// One source for MeshLab 2020.09 and 2025.07 (meshlab_compat.h).
#include <meshlab_compat.h>

class FilterSpherePackPlugin : public QObject, public growth::meshlab::Filter {
  Q_OBJECT
#ifdef GROWTH_MESHLAB_2025
  MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
  Q_INTERFACES(FilterPlugin)
#else
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)
#endif

public:
  enum { FP_SPHERE_PACKING, FP_SPHERE_PACKING_REMESH };
  using FilterID = growth::meshlab::FilterID;

  FilterSpherePackPlugin();

  QString pluginName() const override;
  QString filterName(FilterID filter) const override;
  QString filterInfo(FilterID filter) const override;
  QString pythonName(FilterID filter) const override;
  FilterClass filterClass(FilterID) const override;
  int preConditions(FilterID) const override;
  int postConditions(FilterID) const override;
  void addParameters(FilterID, const MeshModel& m, RichParameterList& parlst) override;
  bool apply(FilterID filter, MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
             growth::meshlab::Outputs& outputs) override;

private:
  bool applySpherePacking(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                          growth::meshlab::Outputs& outputs);
  bool applyRemesh(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                   growth::meshlab::Outputs& outputs);
};
