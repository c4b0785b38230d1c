#pragma once
// One glue source per filter for two generations of MeshLab's filter plugin API:
//   - MeshLab 2020.09: MeshFilterInterface (common/interfaces.h), errors through errorMessage;
//   - MeshLab 2022.02 and later (2025.07, PyMeshLab 2025.7): FilterPlugin
//     (common/plugins/interfaces/filter_plugin.h), errors as MLException, an output dictionary.
// CMake defines GROWTH_MESHLAB_2025 for the second. A filter derives from growth::meshlab::Filter
// and implements the API-neutral hooks below; this header implements each API's virtual functions
// with them. It holds only the differences the two filters of this project need.
#ifdef GROWTH_MESHLAB_2025
#include <common/plugins/interfaces/filter_plugin.h>
#include <common/mlexception.h>
#include <common/parameters/rich_parameter_list.h>
#else
#include <common/interfaces.h>
#endif

#include <QAction>
#include <QString>
#include <QVariant>

#include <map>
#include <string>
#include <utility>

namespace growth {
namespace meshlab {

#ifdef GROWTH_MESHLAB_2025
using FilterBase = ::FilterPlugin;
using FilterID = ::MeshLabPlugin::ActionIDType;
using RichLength = ::RichPercentage; // an absolute length; % of the bounding-box diagonal in the dialog
using RichPoint = ::RichPosition;
#else
using FilterBase = ::MeshFilterInterface;
using FilterID = ::MeshFilterInterface::FilterIDType;
using RichLength = ::RichAbsPerc;
using RichPoint = ::RichPoint3f;
#endif

/// Named results of a filter: PyMeshLab's output dictionary (MeshLab 2020.09 has none and drops them).
using Outputs = std::map<std::string, QVariant>;

class Filter : public FilterBase {
public:
  ~Filter() override {
    for (QAction* a : actionList) delete a;
  }

  // --- Hooks, the same for both APIs -------------------------------------------------------------
  virtual FilterClass filterClass(FilterID) const = 0;
  /// The filter's name in PyMeshLab (MeshLab 2025.07 derives one from filterName() when empty).
  virtual QString pythonName(FilterID) const { return QString(); }
  virtual int preConditions(FilterID) const { return MeshModel::MM_NONE; }
  virtual int requirements(FilterID) const { return MeshModel::MM_NONE; }
  virtual int postConditions(FilterID) const = 0;
  virtual void addParameters(FilterID, const MeshModel& m, RichParameterList& parlst) = 0;
  /// Applies the filter. On failure: set errorMessage and return false (thrown as MLException in 2025).
  virtual bool apply(FilterID, MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                     Outputs& outputs) = 0;

  // --- Helpers ------------------------------------------------------------------------------------
  /// Registers a filter and its menu action; call from the constructor with the plugin as `self`
  /// (MeshLab 2020.09 finds the plugin of an action as the action's parent).
  void addFilter(FilterID id, QObject* self) {
    typeList.push_back(id);
    actionList.push_back(new QAction(filterName(id), self));
  }

  static void removeLayer(MeshDocument& md, MeshModel* m) {
#ifdef GROWTH_MESHLAB_2025
    md.delMesh(m->id());
#else
    md.delMesh(m);
#endif
  }

#ifdef GROWTH_MESHLAB_2025
  /// MeshLab 2020.09's name of the logger, so both APIs' glue logs the same way.
  template <typename... Ts> void Log(Ts&&... ts) const { log(std::forward<Ts>(ts)...); }

  QString errorMessage;

  // --- FilterPlugin (MeshLab 2022.02 and later) -----------------------------------------------------
  /// Shown in Help > Plugin Info (MeshLab's default names its own lab).
  QString vendor() const override { return "growth-meshers"; }
  using FilterBase::pythonFilterName;
  QString pythonFilterName(FilterID f) const override {
    const QString name = pythonName(f);
    return name.isEmpty() ? FilterBase::pythonFilterName(f) : name;
  }
  FilterClass getClass(const QAction* a) const override { return filterClass(ID(a)); }
  int getPreConditions(const QAction* a) const override { return preConditions(ID(a)); }
  int getRequirements(const QAction* a) override { return requirements(ID(a)); }
  int postCondition(const QAction* a) const override { return postConditions(ID(a)); }
  FilterArity filterArity(const QAction*) const override { return SINGLE_MESH; }
  using FilterBase::initParameterList;
  RichParameterList initParameterList(const QAction* a, const MeshModel& m) override {
    RichParameterList parlst;
    addParameters(ID(a), m, parlst);
    return parlst;
  }
  std::map<std::string, QVariant> applyFilter(const QAction* a, const RichParameterList& par, MeshDocument& md,
                                              unsigned int& /*postConditionMask*/, vcg::CallBackPos* cb) override {
    Outputs outputs;
    errorMessage.clear();
    if (!apply(ID(a), md, par, cb, outputs)) throw MLException(errorMessage);
    return outputs;
  }
#else
  // --- MeshFilterInterface (MeshLab 2020.09) --------------------------------------------------------
  FilterClass getClass(QAction* a) override { return filterClass(ID(a)); }
  int getPreConditions(QAction* a) const override { return preConditions(ID(a)); }
  int getRequirements(QAction* a) override { return requirements(ID(a)); }
  int postCondition(QAction* a) const override { return postConditions(ID(a)); }
  FILTER_ARITY filterArity(QAction*) const override { return SINGLE_MESH; }
  void initParameterSet(QAction* a, MeshModel& m, RichParameterList& parlst) override {
    addParameters(ID(a), m, parlst);
  }
  bool applyFilter(QAction* a, MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb) override {
    Outputs outputs;
    return apply(ID(a), md, par, cb, outputs);
  }
#endif
};

} // namespace meshlab
} // namespace growth
