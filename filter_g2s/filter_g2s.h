#pragma once
// MeshLab glue of the Robust G2S mesher: parameters, reading the layer, calling the engine (g2s.h),
// writing the result into a new layer, logging. No algorithm lives here.
#include <common/interfaces.h>

class FilterG2SPlugin : public QObject, public MeshFilterInterface {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)

public:
  enum { FP_ROBUST_G2S };

  FilterG2SPlugin();
  ~FilterG2SPlugin() override;

  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction*) override;
  int getRequirements(QAction*) override;
  int postCondition(QAction*) const override;
  FILTER_ARITY filterArity(QAction*) const override;
  void initParameterSet(QAction*, MeshModel& m, RichParameterList& parlst) override;
  bool applyFilter(QAction* filter, MeshDocument& md, const RichParameterList& par,
                   vcg::CallBackPos* cb) override;

private:
  bool applyRobustG2S(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb);
};
