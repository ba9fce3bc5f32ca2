// hirsute_hair_render_bench: the GL renderer's hairs against the raw line throughput of the same
// GL (docs/design.md, "Benchmarks": hairs as instances of templates, and the benchmark shows the
// layout pays).
//
// The scene is, by default, a seeded synthetic plant: 120 000 hairs of three four-segment
// templates rooted on a fan of stems, pointing out of them (`--hairs N` changes the count), or a
// model's own Scene (`--model plant.l [--view plant.v]`, built as `hirsute render` builds it). The
// renderer draws its hairs as instances (one vertex buffer a template, 24 bytes a hair); the raw
// pass draws the same segments, expanded to world positions in one vertex buffer, as GL_LINES
// with a trivial shader into the same multisampled framebuffer of the same OSMesa context. A frame
// is timed from the draw to glFinish, the first of each left out (llvmpipe compiles its shaders
// there), the two timed in turn, the medians printed; figures are printed, never asserted.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/gl/offscreen.h"
#include "hirsute/viewer/view/camera.h"
#include "model_pipeline.h"
#include "raw_gl.h"
#include "synthetic_hairs.h"

using hirsute::GlFunctions;
using hirsute::bench::frameSeconds;
using hirsute::bench::trivialProgram;

int main(int argc, char** argv) {
  CLI::App app{
      "Frame time of the GL renderer's hairs against the raw line throughput of the same "
      "OSMesa context"};
  std::size_t hairCount = 120'000;
  int frames = 7, samples = 4;
  std::string size = "1024x768", model, view;
  app.add_option("--hairs", hairCount,
                 "Hairs in the synthetic scene (default 120000, 4 segments each)");
  app.add_option("--model", model, "A model's .l file: its own Scene instead of the synthetic one");
  app.add_option("--view", view, "The model's .v file");
  bool hairsOnly = false, shuffledRaw = false;
  app.add_flag("--shuffled-raw", shuffledRaw, "Draw the raw segments in a shuffled hair order");
  app.add_flag(
      "--hairs-only", hairsOnly,
      "Draw only the model's hairs (its surfaces and lines left out), as the raw pass does");
  app.add_option("--frames", frames, "Timed frames of each (default 7; the median is printed)");
  app.add_option("--samples", samples, "Multisample antialiasing samples (default 4, as render)");
  app.add_option("--size", size, "Image size (default 1024x768)");
  CLI11_PARSE(app, argc, argv);
  int width = std::stoi(size.substr(0, size.find('x')));
  int height = std::stoi(size.substr(size.find('x') + 1));

  hirsute::Scene scene;
  hirsute::ViewSettings viewSettings;
  bool materialMode = false;
  if (!model.empty()) {
    hirsute::cli::ModelOptions options;
    options.lsystemFile = model;
    options.viewFile = view;
    hirsute::Diagnostics diagnostics(&std::cerr);
    try {
      hirsute::cli::BuiltScene built = hirsute::cli::buildScene(options, diagnostics);
      scene = std::move(built.scene);
      viewSettings = built.resources.view;
      materialMode = built.resources.materialMode;
      if (hairsOnly) {
        hirsute::Scene hairs;
        hairs.materials = std::move(scene.materials);
        hairs.organ<hirsute::HairPart>().templates =
            std::move(scene.organ<hirsute::HairPart>().templates);
        hairs.organ<hirsute::HairPart>().hairs = std::move(scene.organ<hirsute::HairPart>().hairs);
        scene = std::move(hairs);
      }
    } catch (const hirsute::DiagnosticError& e) {
      std::cerr << e.diagnostic().text() << '\n';
      return 2;
    }
  } else {
    scene = hirsute::bench::syntheticHairScene(hairCount, 20240522);
    viewSettings.viewpoint = {0.3f, 0.2f, 1};
  }

  hirsute::OsMesaContext context;
  const GlFunctions& gl = context.gl();
  hirsute::OffscreenFramebuffer framebuffer(gl, width, height, samples);
  framebuffer.bind();
  std::printf("GL: %s\n", context.description().c_str());
  std::printf(
      "image %dx%d, %d samples, %u hardware threads (llvmpipe uses LP_NUM_THREADS or all)\n", width,
      height, framebuffer.samples(), std::thread::hardware_concurrency());
  std::printf(
      "scene: %s, %zu hairs of %zu templates, %zu triangles, %zu line segments\n\n",
      model.empty() ? "synthetic" : model.c_str(), scene.organ<hirsute::HairPart>().hairs.size(),
      scene.organ<hirsute::HairPart>().templates.size(), scene.triangleCount(), scene.lines.size());

  hirsute::GlRenderer renderer(gl);
  auto uploadStart = std::chrono::steady_clock::now();
  renderer.upload(scene, viewSettings, materialMode);
  gl.Finish();
  double upload =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - uploadStart).count();
  hirsute::Camera camera = hirsute::fitCamera(viewSettings, scene.bounds(), {width, height});

  // The same segments, placed: two world positions a segment, in one buffer.
  std::vector<glm::vec3> ends;
  ends.reserve(renderer.organPrimitives("hairs") * 2);
  // In the Scene's order, or shuffled (--shuffled-raw), as the renderer orders them for its
  // fractions: the order changes how many fragments the depth test passes.
  std::vector<hirsute::Hair> order(scene.organ<hirsute::HairPart>().hairs);
  if (shuffledRaw) {
    std::mt19937 random(7);
    std::shuffle(order.begin(), order.end(), random);
  }
  for (const hirsute::Hair& h : order) {
    if (h.templateIndex >= scene.organ<hirsute::HairPart>().templates.size()) continue;
    glm::mat3 rotation = glm::mat3_cast(h.rotation());
    for (const auto& polyline :
         scene.organ<hirsute::HairPart>().templates[h.templateIndex].polylines) {
      for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        ends.push_back(h.root + h.length * (rotation * polyline[i]));
        ends.push_back(h.root + h.length * (rotation * polyline[i + 1]));
      }
    }
  }
  GLuint program = trivialProgram(gl);
  GLint viewProjection = gl.GetUniformLocation(program, "uViewProjection");
  GLuint vertexArray = 0, vertices = 0;
  gl.GenVertexArrays(1, &vertexArray);
  gl.BindVertexArray(vertexArray);
  gl.GenBuffers(1, &vertices);
  gl.BindBuffer(GL_ARRAY_BUFFER, vertices);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(ends.size() * sizeof(glm::vec3)),
                ends.data(), GL_STATIC_DRAW);
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl.BindVertexArray(0);

  auto drawScene = [&](bool visible, float fraction) {
    return [&renderer, &camera, visible, fraction] {
      renderer.setOrganVisible("hairs", visible);
      renderer.setDetail(fraction);
      renderer.draw(camera);
    };
  };
  auto drawRaw = [&] {
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_BLEND);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.UseProgram(program);
    gl.UniformMatrix4fv(viewProjection, 1, GL_FALSE, glm::value_ptr(camera.viewProjection()));
    gl.BindVertexArray(vertexArray);
    gl.DrawArrays(GL_LINES, 0, static_cast<GLsizei>(ends.size()));
  };
  std::vector<double> t = frameSeconds(
      gl, frames, {drawScene(true, 1.0f), drawRaw, drawScene(false, 1.0f), drawScene(true, 0.25f)});
  double withHairs = t[0], raw = t[1], without = t[2], quarter = t[3];
  std::size_t segments = renderer.organPrimitives("hairs");

  std::printf("hairs: %zu instances, %zu segments (%.1f MB of instances, %.1f MB as raw lines)\n",
              renderer.organInstances("hairs"), segments,
              static_cast<double>(renderer.organInstances("hairs")) * 24 / 1e6,
              static_cast<double>(ends.size() * sizeof(glm::vec3)) / 1e6);
  std::printf("  %-32s %9.1f ms   %7.2f M segments/s\n", "renderer frame:", withHairs * 1e3,
              static_cast<double>(segments) / withHairs / 1e6);
  std::printf("  %-32s %9.1f ms   %7.2f M segments/s\n", "raw GL_LINES, same GL:", raw * 1e3,
              static_cast<double>(segments) / raw / 1e6);
  std::printf("  %-32s %9.2f   (target <= 1.5)\n", "frame / raw:", withHairs / raw);
  std::printf("  %-32s %9.1f ms\n", "renderer frame, hairs hidden:", without * 1e3);
  if (scene.triangleCount() + scene.lines.size() > 0) {
    std::printf("  %-32s %9.2f\n", "(frame - hidden) / raw:", (withHairs - without) / raw);
  }
  std::printf("  %-32s %9.1f ms\n", "renderer frame, fraction 0.25:", quarter * 1e3);
  std::printf("  %-32s %9.1f ms\n", "upload:", upload * 1e3);

  gl.DeleteBuffers(1, &vertices);
  gl.DeleteVertexArrays(1, &vertexArray);
  gl.DeleteProgram(program);
  return 0;
}
