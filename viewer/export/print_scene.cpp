// The walk over the Scene that every format shares (scene_writer.h), with the organs' writers of
// organWriters(), and the formats' entry points that take it. Apart from the printers' library,
// since the organs' writers are built over the printers.
#include "hirsute/viewer/export/blender_writer.h"
#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/export/organ_writer.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/export/scene_writer.h"

namespace hirsute {

void printScene(const Scene& scene, ScenePrinter& printer, Progress* progress, const char* stage) {
  printer.progress_ = progress;
  printer.done_ = 0;
  if (progress != nullptr) {
    std::size_t items = scene.triangleCount() + scene.lines.size() + scene.spheres.size() +
                        scene.discs.size() + scene.labels.size();
    for (const OrganWriter* organ : organWriters()) items += organ->items(scene);
    progress->begin(stage, Progress::Unit::Percent, static_cast<double>(items));
  }
  printer.beginScene(scene, organWriters());
  for (const TriangleMesh& mesh : scene.meshes) {
    if (mesh.triangleCount() == 0) continue;
    printer.mesh(mesh);
    printer.advance(static_cast<double>(mesh.triangleCount()));
  }
  for (const LineSegment& line : scene.lines) {
    printer.line(line, scene.lineStyle);
    printer.advance();
  }
  for (const Sphere& sphere : scene.spheres) {
    printer.sphere(sphere);
    printer.advance();
  }
  for (const Disc& disc : scene.discs) {
    printer.disc(disc);
    printer.advance();
  }
  for (const Label& label : scene.labels) printer.label(label);
  printer.advance(static_cast<double>(scene.labels.size()));
  for (const OrganWriter* organ : organWriters()) {
    const std::size_t items = organ->items(scene);
    if (items == 0) continue;
    // The writer advances item by item if it can; after it, the count is right either way.
    const double before = printer.done_;
    printer.organ(*organ, scene);
    printer.done_ = before;
    printer.advance(static_cast<double>(items));
  }
  printer.endScene();
  printer.progress_ = nullptr;
}

PovExportStats writePov(const Scene& scene, const PovOptions& options,
                        const std::filesystem::path& target, Progress* progress) {
  PovWriter writer(target, options);
  printScene(scene, writer, progress, "writing POV-Ray");
  return writer.stats();
}

ObjExportStats writeObj(const Scene& scene, const std::filesystem::path& target, ObjOptions options,
                        Progress* progress) {
  ObjWriter writer(target, options);
  printScene(scene, writer, progress, "writing OBJ");
  return writer.stats();
}

BlenderExportStats writeBlender(const Scene& scene, const BlenderOptions& options,
                                const std::filesystem::path& target, Progress* progress) {
  BlenderWriter writer(target, options);
  printScene(scene, writer, progress, "writing Blender");
  return writer.stats();
}

}  // namespace hirsute
