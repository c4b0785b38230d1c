// plugin_params: loads a filter plugin the way MeshLab does (QPluginLoader + MeshFilterInterface),
// asks it for its parameters on a given point cloud, and prints them.
//
//   plugin_params <plugin.so> <cloud.ply>          one line per parameter: filter<TAB>name<TAB>type<TAB>description
//   plugin_params --mlx <plugin.so> <cloud.ply>    a complete .mlx script with every parameter at its default
//
// The integration tests use it to check that scripts/mlx/*.mlx list exactly the filters' parameters
// and that meshlabserver shows them.
#include <common/interfaces.h>

#include <growth/meshlab/layer.h>
#include <growth/cloud_generator.h>

#include <QCoreApplication>
#include <QDomDocument>
#include <QFileInfo>
#include <QPluginLoader>
#include <QTextStream>

#include <vcg/complex/algorithms/update/bounding.h>
#include <wrap/io_trimesh/import_ply.h>

#include <cstdio>

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  bool mlx = false;
  int a = 1;
  if (argc > 1 && QString(argv[1]) == "--mlx") mlx = true, ++a;
  if (argc - a != 2) {
    std::fprintf(stderr, "usage: plugin_params [--mlx] <plugin.so> <cloud.ply>\n");
    return 2;
  }
  QPluginLoader loader(QFileInfo(QString::fromLocal8Bit(argv[a])).absoluteFilePath());
  QObject* instance = loader.instance();
  auto* filter = qobject_cast<MeshFilterInterface*>(instance);
  if (filter == nullptr) {
    std::fprintf(stderr, "plugin_params: %s is not a MeshLab filter plugin: %s\n", argv[a],
                 qUtf8Printable(loader.errorString()));
    return 1;
  }
  MeshDocument md;
  MeshModel* m = md.addNewMesh("", "cloud", true);
  int mask = 0;
  if (vcg::tri::io::ImporterPLY<CMeshO>::Open(m->cm, argv[a + 1], mask) != 0) {
    std::fprintf(stderr, "plugin_params: cannot read %s\n", argv[a + 1]);
    return 1;
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(m->cm);

  QDomDocument doc("FilterScript");
  QDomElement root = doc.createElement("FilterScript");
  doc.appendChild(root);
  for (QAction* action : filter->actions()) {
    RichParameterList params;
    filter->initParameterSet(action, md, params);
    QDomElement tag = doc.createElement("filter");
    tag.setAttribute("name", action->text());
    for (const RichParameter& p : params) {
      if (mlx)
        tag.appendChild(p.fillToXMLDocument(doc, false));
      else
        std::printf("%s\t%s\t%s\t%s\n", qUtf8Printable(action->text()), qUtf8Printable(p.name()),
                    qUtf8Printable(p.stringType()), qUtf8Printable(p.fieldDescription()));
    }
    root.appendChild(tag);
  }
  if (mlx) {
    QTextStream out(stdout);
    doc.save(out, 1);
  }
  return 0;
}
