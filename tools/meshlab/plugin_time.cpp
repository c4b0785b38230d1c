// plugin_time: times one filter of a MeshLab filter plugin in process, the way meshlabserver applies
// it (QPluginLoader + MeshFilterInterface: defaults from initParameterSet, overridden by the values of
// an .mlx script, getRequirements → updateDataMask, then applyFilter), with one steady clock around
// applyFilter only. Each repeat starts from a freshly loaded cloud; the fastest repeat is reported.
//
//   plugin_time <plugin.so> <script.mlx> <cloud.ply> [--repeat R] [--min-seconds S] [--min-repeats K]
//
// The benchmark uses it for clouds whose filter time is too short for a wall-clock difference of
// meshlabserver runs (resolution 0.01 s): MeshLab's Ball Pivoting and our filters are then timed by
// the same clock, around the same call. Prints `key: value` lines (seconds = fastest repeat).
#include <common/GLLogStream.h>
#include <common/filterscript.h>
#include <common/interfaces.h>

#include <QApplication>
#include <QFileInfo>
#include <QPluginLoader>

#include <vcg/complex/algorithms/update/bounding.h>
#include <wrap/io_trimesh/import_ply.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

// meshlabserver passes a callback that prints; some filters (Ball Pivoting) call it without a
// null check, so one is needed. This one does nothing, so that it costs nothing measurable.
bool quietCallback(const int, const char*) { return true; }

int usage() {
  std::fprintf(stderr, "usage: plugin_time <plugin.so> <script.mlx> <cloud.ply> [--repeat R] [--min-seconds S]\n"
                       "                   [--min-repeats K]\n"
                       "  R: repeats (default 5); S: keep repeating, up to R, until this much filter time\n"
                       "  was spent (default 0: always R), but at least K times (default 1)\n");
  return 2;
}

} // namespace

int main(int argc, char** argv) {
  // Some filter plugins create QActions with shortcuts, which needs a GUI application; no window is
  // shown, so Qt's offscreen platform serves unless the caller chose one.
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  if (argc < 4) return usage();
  int repeat = 5;
  double minSeconds = 0;
  int minRepeats = 1;
  for (int a = 4; a < argc; ++a) {
    if (std::strcmp(argv[a], "--repeat") == 0 && a + 1 < argc) repeat = std::max(1, std::atoi(argv[++a]));
    else if (std::strcmp(argv[a], "--min-seconds") == 0 && a + 1 < argc) minSeconds = std::atof(argv[++a]);
    else if (std::strcmp(argv[a], "--min-repeats") == 0 && a + 1 < argc) minRepeats = std::max(1, std::atoi(argv[++a]));
    else return usage();
  }
  QPluginLoader loader(QFileInfo(QString::fromLocal8Bit(argv[1])).absoluteFilePath());
  auto* filter = qobject_cast<MeshFilterInterface*>(loader.instance());
  if (filter == nullptr) {
    std::fprintf(stderr, "plugin_time: %s is not a MeshLab filter plugin: %s\n", argv[1],
                 qUtf8Printable(loader.errorString()));
    return 1;
  }
  FilterScript script;
  if (!script.open(QString::fromLocal8Bit(argv[2])) || script.size() != 1) {
    std::fprintf(stderr, "plugin_time: %s must be an .mlx script with exactly one filter\n", argv[2]);
    return 1;
  }
  const QString name = script.front().filterName();
  QAction* action = nullptr;
  for (QAction* a : filter->actions())
    if (a->text() == name) action = a;
  if (action == nullptr) {
    std::fprintf(stderr, "plugin_time: %s has no filter named '%s'\n", argv[1], qUtf8Printable(name));
    return 1;
  }

  std::vector<double> times;
  double spent = 0;
  int faces = 0, vertices = 0, layers = 0;
  for (int r = 0; r < repeat && (r < minRepeats || minSeconds <= 0 || spent < minSeconds); ++r) {
    MeshDocument md;
    MeshModel* m = md.addNewMesh("", "cloud", true);
    int mask = 0;
    if (vcg::tri::io::ImporterPLY<CMeshO>::Open(m->cm, argv[3], mask) != 0) {
      std::fprintf(stderr, "plugin_time: cannot read %s\n", argv[3]);
      return 1;
    }
    m->Enable(mask);
    vcg::tri::UpdateBounding<CMeshO>::Box(m->cm);
    // Parameters as meshlabserver sets them: the filter's defaults for this document, then the
    // script's values.
    RichParameterList params;
    filter->initParameterSet(action, md, params);
    for (const RichParameter& p : script.front().second)
      if (params.hasParameter(p.name())) params.setValue(p.name(), p.value());
    m->updateDataMask(filter->getRequirements(action));
    GLLogStream log;
    filter->setLog(&log);

    const auto start = std::chrono::steady_clock::now();
    const bool ok = filter->applyFilter(action, md, params, quietCallback);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    filter->setLog(nullptr);
    if (!ok) {
      std::fprintf(stderr, "plugin_time: the filter failed: %s\n", qUtf8Printable(filter->errorMsg()));
      return 1;
    }
    times.push_back(seconds);
    spent += seconds;
    faces = md.mm()->cm.fn;
    vertices = md.mm()->cm.vn;
    layers = md.size();
  }
  std::printf("filter: %s\n", qUtf8Printable(name));
  std::printf("seconds: %.6f\n", *std::min_element(times.begin(), times.end()));
  std::printf("repeats:");
  for (double t : times) std::printf(" %.6f", t);
  std::printf("\nlayers: %d\nvertices: %d\nfaces: %d\n", layers, vertices, faces);
  return 0;
}
