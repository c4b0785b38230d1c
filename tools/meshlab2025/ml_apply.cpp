// ml_apply: loads a filter plugin the way PyMeshLab 2025.7's pymeshlab.load_plugin does and applies
// one of its filters to a PLY file, on MeshLab 2025.07's libmeshlab-common: built against the
// double-precision SDK (build/meshlab-2025.07d/ml_apply, as PyMeshLab 2025.7 and MeshLab 2025.07d)
// or the single-precision one (build/meshlab-2025.07/ml_apply, as the plain MeshLab 2025.07 GUI).
//
//   ml_apply PLUGIN.so "FILTER NAME" IN.ply OUT.ply [name=value ...]
//
// Steps, as in PyMeshLab: PluginManager::checkPlugin (Qt plugin, MeshLab plugin, same scalar
// precision, same first six characters of the MeshLab version, valid filter plugin), then
// PluginManager::loadPlugin; the filter is found by its name or its Python name; its parameters are
// the plugin's defaults for the loaded mesh (initParameterList on the MeshDocument), overridden by
// name=value, by MeshLab or Python name (RichPercentage parameters take absolute values, positions
// x,y,z, booleans true/false); the filter's requirements are enabled, its preconditions checked, applyFilter runs
// on the MeshDocument, and the current layer afterwards is saved as binary PLY (with per-face
// quality when the layer has it). Prints the parameters with their dialog texts and their Python
// names and types (as PyMeshLab derives them), the filter's log and its output values.
// Exit status: 0 on success, 1 when the filter fails, 2 on bad usage or input.
#include <common/GLLogStream.h>
#include <common/globals.h>
#include <common/ml_document/mesh_document.h>
#include <common/mlexception.h>
#include <common/parameters/rich_parameter_list.h>
#include <common/parameters/value/bool_value.h>
#include <common/parameters/value/float_value.h>
#include <common/parameters/value/int_value.h>
#include <common/parameters/value/point3_value.h>
#include <common/plugins/interfaces/filter_plugin.h>
#include <common/plugins/plugin_manager.h>

#include <QCoreApplication>
#include <QStringList>

#include <vcg/complex/algorithms/update/bounding.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_ply.h>

#include <cstdio>
#include <memory>

namespace {

int usage() {
  std::fprintf(stderr, "usage: ml_apply PLUGIN.so \"FILTER NAME\" IN.ply OUT.ply [name=value ...]\n");
  return 2;
}

// Sets one parameter from its text; returns an error message, empty on success.
// `given` is the parameter's MeshLab name or its Python name (RichParameter::pythonName(), the
// keyword of PyMeshLab's apply_filter).
QString setParameter(RichParameterList& par, const QString& given, const QString& text) {
  QString name;
  for (const RichParameter& p : par)
    if (p.name() == given || p.pythonName() == given) name = p.name();
  if (name.isEmpty()) {
    QStringList names;
    for (const RichParameter& p : par) names << p.name();
    return "no parameter '" + given + "'; the filter has: " + names.join(", ");
  }
  const Value& v = par.getParameterByName(name).value();
  bool ok = true;
  if (v.isBool()) {
    const QString t = text.toLower();
    ok = t == "true" || t == "false" || t == "1" || t == "0";
    if (ok) par.setValue(name, BoolValue(t == "true" || t == "1"));
  } else if (v.isInt()) {
    const int i = text.toInt(&ok);
    if (ok) par.setValue(name, IntValue(i));
  } else if (v.isFloat()) {
    const double f = text.toDouble(&ok);
    if (ok) par.setValue(name, FloatValue(float(f)));
  } else if (v.isPoint3()) {
    const QStringList xyz = text.split(',');
    ok = xyz.size() == 3;
    Point3m p;
    for (int k = 0; ok && k < 3; ++k) p[k] = xyz[k].toDouble(&ok);
    if (ok) par.setValue(name, Point3Value(p));
  } else {
    return "parameter '" + name + "' has a type ml_apply does not set (" +
           par.getParameterByName(name).stringType() + ")";
  }
  return ok ? QString() : "cannot read '" + text + "' as the value of '" + name + "'";
}

void printLog(const GLLogStream& log) {
  for (const auto& entry : log.logStringList())
    std::printf("%s%s\n", entry.first == GLLogStream::WARNING ? "log warning: " : "log: ",
                qUtf8Printable(entry.second));
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 5) return usage();
  // A QCoreApplication, as PyMeshLab has: the plugins' QActions need no GUI, and the wheel's Qt
  // ships no platform plugin (not even "offscreen") that a QApplication could start on.
  QCoreApplication app(argc, argv);
  const QString pluginPath = QString::fromLocal8Bit(argv[1]);
  const QString filterName = QString::fromLocal8Bit(argv[2]);
  const char* inPath = argv[3];
  const char* outPath = argv[4];

  std::printf("host: MeshLab %s, %s precision\n", meshlab::meshlabVersion().c_str(),
              meshlab::builtWithDoublePrecision() ? "double" : "single");
  PluginManager pm;
  FilterPlugin* fp = nullptr;
  try {
    PluginManager::checkPlugin(pluginPath); // what pymeshlab.load_plugin runs first
    MeshLabPlugin* plugin = pm.loadPlugin(pluginPath);
    const auto version = plugin->getMLVersion();
    std::printf("plugin: %s, built for MeshLab %s, %s precision\n", qUtf8Printable(plugin->pluginName()),
                version.first.c_str(), version.second ? "double" : "single");
    fp = dynamic_cast<FilterPlugin*>(plugin);
  } catch (const MLException& e) {
    std::fprintf(stderr, "ml_apply: the plugin was refused: %s\n", e.what());
    return 2;
  }
  if (fp == nullptr) {
    std::fprintf(stderr, "ml_apply: %s is not a filter plugin\n", argv[1]);
    return 2;
  }
  QAction* action = nullptr;
  QStringList names;
  for (QAction* a : fp->actions()) {
    names << fp->filterName(a) + " (" + fp->pythonFilterName(a) + ")";
    if (fp->filterName(a) == filterName || fp->pythonFilterName(a) == filterName) action = a;
  }
  if (action == nullptr) {
    std::fprintf(stderr, "ml_apply: no filter '%s'; the plugin has: %s\n", argv[2], qUtf8Printable(names.join("; ")));
    return 2;
  }

  MeshDocument md;
  MeshModel* mm = md.addNewMesh(QString::fromLocal8Bit(inPath), QFileInfo(inPath).completeBaseName(), true);
  int mask = 0;
  if (!vcg::tri::io::ImporterPLY<CMeshO>::LoadMask(inPath, mask)) {
    std::fprintf(stderr, "ml_apply: cannot read %s\n", inPath);
    return 2;
  }
  mm->enable(mask);
  if (vcg::tri::io::ImporterPLY<CMeshO>::Open(mm->cm, inPath, mask) != 0) {
    std::fprintf(stderr, "ml_apply: cannot read %s: %s\n", inPath,
                 vcg::tri::io::ImporterPLY<CMeshO>::ErrorMsg(vcg::tri::io::ImporterPLY<CMeshO>::Open(mm->cm, inPath, mask)));
    return 2;
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(mm->cm);
  std::printf("input: %s, %d vertices, %d faces\n", inPath, mm->cm.vn, mm->cm.fn);

  RichParameterList par = fp->initParameterList(action, md);
  for (int k = 5; k < argc; ++k) {
    const QString arg = QString::fromLocal8Bit(argv[k]);
    const int eq = arg.indexOf('=');
    const QString error = eq <= 0 ? "expected name=value, got '" + arg + "'"
                                  : setParameter(par, arg.left(eq), arg.mid(eq + 1));
    if (!error.isEmpty()) {
      std::fprintf(stderr, "ml_apply: %s\n", qUtf8Printable(error));
      return 2;
    }
  }
  for (const RichParameter& p : par) {
    const Value& v = p.value();
    QString text;
    if (v.isBool()) text = v.getBool() ? "true" : "false";
    else if (v.isInt()) text = QString::number(v.getInt());
    else if (v.isFloat()) text = QString::number(v.getFloat(), 'g', 9);
    else if (v.isPoint3()) text = QString("%1,%2,%3").arg(v.getPoint3()[0]).arg(v.getPoint3()[1]).arg(v.getPoint3()[2]);
    else text = "(" + p.stringType() + ")";
    std::printf("parameter %s = %s\n", qUtf8Printable(p.name()), qUtf8Printable(text));
    std::printf("python %s: %s: %s\n", qUtf8Printable(p.name()), qUtf8Printable(p.pythonName()),
                qUtf8Printable(p.pythonType()));
    std::printf("help %s: %s: %s\n", qUtf8Printable(p.name()), qUtf8Printable(p.fieldDescription()),
                qUtf8Printable(p.toolTip()));
  }

  mm->updateDataMask(fp->getRequirements(action));
  QStringList missing;
  if (!fp->isFilterApplicable(action, *md.mm(), missing)) {
    std::fprintf(stderr, "ml_apply: the filter needs what the mesh lacks: %s\n", qUtf8Printable(missing.join(", ")));
    return 2;
  }

  GLLogStream log;
  fp->setLog(&log);
  unsigned int postConditionMask = fp->postCondition(action);
  std::map<std::string, QVariant> outputs;
  try {
    outputs = fp->applyFilter(action, par, md, postConditionMask, nullptr);
  } catch (const MLException& e) {
    printLog(log);
    std::fprintf(stderr, "ml_apply: the filter failed: %s\n", e.what());
    return 1;
  }
  printLog(log);
  for (const auto& kv : outputs) std::printf("output %s = %s\n", kv.first.c_str(), qUtf8Printable(kv.second.toString()));

  MeshModel* result = md.mm();
  int saveMask = vcg::tri::io::Mask::IOM_VERTCOORD | vcg::tri::io::Mask::IOM_FACEINDEX;
  if (result->hasDataMask(MeshModel::MM_VERTNORMAL)) saveMask |= vcg::tri::io::Mask::IOM_VERTNORMAL;
  if (result->hasDataMask(MeshModel::MM_FACEQUALITY)) saveMask |= vcg::tri::io::Mask::IOM_FACEQUALITY;
  if (vcg::tri::io::ExporterPLY<CMeshO>::Save(result->cm, outPath, saveMask, true) != 0) {
    std::fprintf(stderr, "ml_apply: cannot write %s\n", outPath);
    return 2;
  }
  std::printf("saved: %s (layer '%s'), %d vertices, %d faces\n", outPath, qUtf8Printable(result->label()),
              result->cm.vn, result->cm.fn);
  return 0;
}
