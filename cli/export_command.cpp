// `hirsute export`: the model's Scene written as a POV-Ray 3.7 scene and/or a Wavefront OBJ with
// its material library and/or a scene file for Blender and/or its surfaces as glTF 2.0 and/or
// its organs as CSV tables (docs/export.md), and, with --render, the POV-Ray scene rendered by
// the installed povray.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "command.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/core/output_target.h"
#include "hirsute/viewer/export/blender_writer.h"
#include "hirsute/viewer/export/gltf_writer.h"
#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/export/organ_writer.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/export/povray_runner.h"
#include "hirsute/viewer/view/png_image.h"
#include "model_pipeline.h"

namespace hirsute::cli {
namespace {

struct ExportOptions {
  ModelOptions model;
  std::string pov;
  std::string obj;
  std::string blender;  // the scene file for Blender (blender_writer.h)
  std::string gltf;     // the surfaces as glTF 2.0 (gltf_writer.h)
  // The organs' tables (organ_writer.h), one file name a writer of organWriters() (empty: none).
  std::vector<std::string> tables = std::vector<std::string>(organWriters().size());
  bool render = false;
  std::string image;         // --render's picture (empty: the .pov's name with .png)
  bool traceLights = false;  // the path tracer's lights (PovOptions::traceLights)
  int width = 800, height = 600;
  int renderTimeout = 3600;  // seconds POV-Ray may run for --render
};

int runExport(ExportOptions o) {
  Progress progress = Progress::onTerminal(stderr);
  o.model.terminalProgress = &progress;
  Diagnostics diagnostics(&std::cerr);
  std::optional<BuiltScene> built = buildSceneOrSay(o.model, diagnostics, progress);
  if (!built) return kExitBadInput;
  try {
    // Every file asked for is written, then all are renamed into place: a run that fails on
    // one leaves every one of them as it was (output_target.h).
    OutputGroup outputs;
    if (!o.pov.empty()) {
      PovOptions options;
      options.group = &outputs;
      options.view = built->resources.view;
      options.materialMode = built->resources.materialMode;
      options.colorMapFile = built->resources.colorMapFile;
      options.width = o.width;
      options.height = o.height;
      options.traceLights = o.traceLights;
      writePov(built->scene, options, o.pov, &progress);
    }
    if (!o.obj.empty()) {
      ObjOptions options;
      options.group = &outputs;
      writeObj(built->scene, o.obj, options, &progress);
    }
    if (!o.blender.empty()) {
      BlenderOptions options;
      options.group = &outputs;
      options.view = built->resources.view;
      options.materialMode = built->resources.materialMode;
      options.width = o.width;
      options.height = o.height;
      writeBlender(built->scene, options, o.blender, &progress);
    }
    if (!o.gltf.empty()) {
      GltfOptions options;
      options.group = &outputs;
      options.view = built->resources.view;
      options.width = o.width;
      options.height = o.height;
      writeGltf(built->scene, options, o.gltf, &progress);
    }
    for (std::size_t k = 0; k < o.tables.size(); ++k) {
      if (o.tables[k].empty()) continue;
      organWriters()[k]->table()->write(built->scene, o.tables[k], &progress, &outputs);
    }
    outputs.commit();
    progress.clear();
  } catch (const std::invalid_argument& e) {
    progress.clear();
    // The model produced geometry no format can hold (a coordinate that is not a number).
    std::cerr << o.model.lsystemFile << ": error: cannot export: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const GeometryLimitError& e) {
    // An organ's geometry, built at the picture's detail, passed --max-vertices.
    progress.clear();
    std::cerr << o.model.lsystemFile << ": error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::runtime_error& e) {
    progress.clear();
    std::cerr << e.what() << '\n';
    return kExitIoError;
  }
  if (!o.render) return kExitOk;

  if (!povrayAvailable()) {
    std::cerr << "hirsute: error: --render runs POV-Ray, and `povray` is not on the PATH (apt "
                 "install povray)\n";
    return kExitIoError;
  }
  std::filesystem::path image = o.image;
  if (image.empty()) {
    // A name derived from the scene's: an image already there is replaced, and the user is told.
    image = std::filesystem::path(o.pov).replace_extension(".png");
    std::error_code error;
    if (std::filesystem::exists(std::filesystem::symlink_status(image, error)) && !error) {
      std::cerr << "hirsute: note: replacing " << printableText(image.string())
                << " with the picture of " << printableText(o.pov)
                << " (--image FILE writes it elsewhere)\n";
    }
  }
  PovrayRun run = runPovray(o.pov, image, o.width, o.height, true,
                            std::chrono::seconds(o.renderTimeout), &progress);
  // POV-Ray's messages quote the scene: its control bytes are shown escaped.
  std::cerr << printableText(run.messages);
  if (run.interruptedBy != 0) {
    std::cerr << "hirsute: stopped by signal " << run.interruptedBy << "; POV-Ray was ended\n";
    return 128 + run.interruptedBy;
  }
  if (run.timedOut) {
    std::cerr << printableText(o.pov) << ": error: POV-Ray ran for more than " << o.renderTimeout
              << " s (--render-timeout) and was stopped; no image was written\n";
    return kExitIoError;
  }
  if (run.exitStatus != 0) {
    std::cerr << printableText(o.pov) << ": error: povray failed (exit status " << run.exitStatus
              << ")\n";
    return kExitIoError;
  }
  return kExitOk;
}

}  // namespace

void registerExportCommand(CLI::App& app, Action& action) {
  auto options = std::make_shared<ExportOptions>();
  // The organs' table options, as the help and the error name them: "--hairs, --feathers".
  std::string tableOptions, tableFiles;
  for (const OrganWriter* writer : organWriters()) {
    if (const std::optional<OrganTable> table = writer->table()) {
      tableOptions += (tableOptions.empty() ? "" : ", ") + std::string(table->option);
      tableFiles += " or " + std::string(table->option) + " FILE";
    }
  }
  CLI::App* command = app.add_subcommand(
      "export",
      "Write the model as a POV-Ray 3.7 scene (--pov), a Wavefront OBJ with its .mtl "
      "(--obj), a scene file for Blender (--blender), its surfaces as glTF (--gltf) and/or its "
      "organs as CSV tables (" +
          tableOptions + ")");
  addModelOptions(*command, options->model);
  command->add_option("--pov", options->pov, "Write a POV-Ray 3.7 scene to FILE (.pov)");
  command->add_option(
      "--obj", options->obj,
      "Write a Wavefront OBJ to FILE (.obj) and its material library beside it (.mtl)");
  command->add_option("--blender", options->blender,
                      "Write a scene file for Blender to FILE: meshes, hairs, fur and barbs as "
                      "curves, the camera and lights; blender/hirsute_import.py reads it");
  command
      ->add_option("--gltf", options->gltf,
                   "Write the surfaces as glTF 2.0 to FILE.gltf (and its buffer FILE.bin) or "
                   "FILE.glb: meshes, normals, materials and the camera; no hairs, fur or "
                   "feathers")
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            try {
              gltfIsBinary(name);
              return {};
            } catch (const std::invalid_argument&) {
              return "'" + name + "': a glTF file's name ends in .gltf or .glb";
            }
          },
          "FILE.gltf|FILE.glb"));
  for (std::size_t k = 0; k < organWriters().size(); ++k) {
    if (const std::optional<OrganTable> table = organWriters()[k]->table())
      command->add_option(table->option, options->tables[k], table->help);
  }
  command
      ->add_flag("--trace-lights", options->traceLights,
                 "Light the POV-Ray scene as render --trace does: an area light, the sky by "
                 "radiosity, translucent colours by backside diffuse")
      ->needs(command->get_option("--pov"));
  CLI::Option* render = command->add_flag(
      "--render", options->render,
      "Render the POV-Ray scene with the installed povray, to the .pov's name with .png");
  render->needs(command->get_option("--pov"));
  command
      ->add_option("--image", options->image,
                   "The PNG file --render writes (default: the .pov's name with .png)")
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            if (imageFormatOf(name) == ImageFormat::Png) return {};
            return "'" + name + "': POV-Ray's picture is a PNG: a name ending in .png";
          },
          "FILE.png"))
      ->needs(render);
  command
      ->add_option("--render-timeout", options->renderTimeout,
                   "Seconds POV-Ray may run for --render before it is stopped (default 3600)")
      ->check(CLI::Range(1, 7 * 24 * 3600))
      ->needs(render);
  addImageSizeOption(*command, options->width, options->height,
                     "The picture's size in pixels, WIDTHxHEIGHT: the camera's aspect, the size "
                     "of pixel-wide lines, --render (default 800x600)");
  command->callback([options, &action, tableFiles] {
    const bool noTable = std::all_of(options->tables.begin(), options->tables.end(),
                                     [](const std::string& file) { return file.empty(); });
    if (options->pov.empty() && options->obj.empty() && options->blender.empty() &&
        options->gltf.empty() && noTable) {
      throw CLI::ValidationError(
          "export needs an output: --pov FILE or --obj FILE or --blender FILE or --gltf FILE" +
          tableFiles + " (or several)");
    }
    action = [options] { return runExport(*options); };
  });
}

}  // namespace hirsute::cli
