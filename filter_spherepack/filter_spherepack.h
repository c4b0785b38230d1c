#pragma once
// MeshLab glue of the sphere-packing mesher: parameters, reading the layer, calling the engine
// (sphere_packer.h), writing the result into a new layer, logging. No algorithm lives here.
#include <common/interfaces.h>

class FilterSpherePackPlugin : public QObject, public MeshFilterInterface {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)

public:
  enum { FP_SPHERE_PACKING };

  FilterSpherePackPlugin();
  ~FilterSpherePackPlugin() override;

  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction*) override;
  int getPreConditions(QAction*) const override;
  int getRequirements(QAction*) override;
  int postCondition(QAction*) const override;
  FILTER_ARITY filterArity(QAction*) const override;
  void initParameterSet(QAction*, MeshModel& m, RichParameterList& parlst) override;
  bool applyFilter(QAction* filter, MeshDocument& md, const RichParameterList& par,
                   vcg::CallBackPos* cb) override;

private:
  bool applySpherePacking(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb);
};
