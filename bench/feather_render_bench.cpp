// The renderer's frame time for a model's feathers (default models/feather-coat/hexagonal, the
// 64-feather coat of Streit & Heidrich's Fig. 15) against the raw throughput of the same GL: the
// same shaft triangles and barb lines or strip triangles, as the renderer built them for the
// camera, drawn with a trivial shader (bench/raw_gl.h) in the same OSMesa context, frame for
// frame. Also the feathers' build time (blending, growth and geometry at the camera's level of
// detail, on the first frame) and their bytes.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <glm/gtc/type_ptr.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/gl/offscreen.h"
#include "hirsute/viewer/view/feather_buffers.h"
#include "model_pipeline.h"
#include "raw_gl.h"

int main(int argc, char** argv) {
  using namespace hirsute;
  using bench::frameSeconds;
  using bench::trivialProgram;
  std::string model = std::string(HIRSUTE_SOURCE_DIR) + "/models/feather-coat/hexagonal.l";
  std::string view = std::string(HIRSUTE_SOURCE_DIR) + "/models/feather-coat/hexagonal.v";
  int frames = 7, samples = 4;
  std::string size = "1024x768";
  CLI::App app{"Frame time of a model's feathers against raw GL throughput of the same primitives"};
  app.add_option("--model", model, "The model's .l file (default models/feather-coat/hexagonal.l)");
  app.add_option("--view", view, "The model's .v file");
  app.add_option("--frames", frames, "Timed frames of each (default 7; the median is printed)");
  app.add_option("--samples", samples, "Multisample antialiasing samples (default 4, as render)");
  app.add_option("--size", size, "Image size (default 1024x768)");
  CLI11_PARSE(app, argc, argv);
  const int width = std::stoi(size.substr(0, size.find('x')));
  const int height = std::stoi(size.substr(size.find('x') + 1));

  cli::ModelOptions options;
  options.lsystemFile = model;
  options.viewFile = view;
  Diagnostics diagnostics(&std::cerr);
  cli::BuiltScene built;
  try {
    built = cli::buildScene(options, diagnostics);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return 2;
  }
  const Scene& scene = built.scene;

  OsMesaContext context;
  const GlFunctions& gl = context.gl();
  OffscreenFramebuffer framebuffer(gl, width, height, samples);
  framebuffer.bind();
  std::printf("GL: %s\nimage %dx%d, %d samples\n", context.description().c_str(), width, height,
              framebuffer.samples());
  GlRenderer renderer(gl);
  renderer.upload(scene, built.resources.view, built.resources.materialMode);
  const Camera camera = fitCamera(built.resources.view, scene.bounds(), {width, height});
  auto buildStart = std::chrono::steady_clock::now();
  renderer.draw(camera);  // the first frame builds the feathers for this camera
  gl.Finish();
  const double firstFrame =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count();

  // The same primitives, as the renderer builds them for this camera.
  const FeatherBuffers buffers = buildFeatherBuffers(scene, featherDetailLevels(scene, camera));
  std::vector<std::uint32_t> barbIndices;
  std::vector<FeatherDrawRun> runs;
  orderFeatherBarbs(buffers, camera, barbIndices, runs);
  GLuint program = trivialProgram(gl);
  GLint viewProjection = gl.GetUniformLocation(program, "uViewProjection");
  GLuint arrays[2] = {}, vertexBuffers[4] = {};
  gl.GenVertexArrays(2, arrays);
  gl.GenBuffers(4, vertexBuffers);
  auto upload = [&](GLuint array, GLuint vertices, GLuint indices,
                    const std::vector<glm::vec3>& positions,
                    const std::vector<std::uint32_t>& order) {
    gl.BindVertexArray(array);
    gl.BindBuffer(GL_ARRAY_BUFFER, vertices);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(positions.size() * sizeof(glm::vec3)),
                  positions.data(), GL_STATIC_DRAW);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                  static_cast<GLsizeiptr>(order.size() * sizeof(std::uint32_t)), order.data(),
                  GL_STATIC_DRAW);
  };
  upload(arrays[0], vertexBuffers[0], vertexBuffers[1], buffers.shaftPositions,
         buffers.shaftIndices);
  upload(arrays[1], vertexBuffers[2], vertexBuffers[3], buffers.barbPositions, barbIndices);
  gl.BindVertexArray(0);

  auto drawScene = [&] { renderer.draw(camera); };
  auto drawRaw = [&] {
    gl.Enable(GL_DEPTH_TEST);
    gl.Disable(GL_BLEND);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.UseProgram(program);
    gl.UniformMatrix4fv(viewProjection, 1, GL_FALSE, glm::value_ptr(camera.viewProjection()));
    gl.BindVertexArray(arrays[0]);
    gl.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(buffers.shaftIndices.size()),
                    GL_UNSIGNED_INT, nullptr);
    gl.BindVertexArray(arrays[1]);
    for (const FeatherDrawRun& run : runs) {
      gl.DrawElements(run.triangles ? GL_TRIANGLES : GL_LINES, static_cast<GLsizei>(run.count),
                      GL_UNSIGNED_INT,
                      reinterpret_cast<const void*>(run.first * sizeof(std::uint32_t)));
    }
  };
  renderer.setOrganVisible("feathers", false);
  auto drawHidden = [&] { renderer.draw(camera); };
  renderer.setOrganVisible("feathers", true);
  const std::vector<double> t = frameSeconds(gl, frames, {drawScene, drawRaw});
  renderer.setOrganVisible("feathers", false);
  const std::vector<double> hidden = frameSeconds(gl, frames, {drawHidden});

  std::printf(
      "scene: %s, %zu feathers (%zu in coats), %zu barbs, %zu barb segments, %zu shaft "
      "triangles, %zu barb index entries\n",
      model.c_str(), scene.organ<FeatherPart>().feathers.size(),
      static_cast<std::size_t>(std::count_if(
          scene.organ<FeatherPart>().feathers.begin(), scene.organ<FeatherPart>().feathers.end(),
          [](const Feather& f) { return f.origin == FeatherOrigin::Coat; })),
      buffers.barbCount, buffers.barbSegments, buffers.shaftTriangles(), barbIndices.size());
  std::printf("  %-34s %9.1f ms\n", "first frame (builds the feathers):", firstFrame * 1e3);
  std::printf("  %-34s %9.1f ms\n", "renderer frame:", t[0] * 1e3);
  std::printf("  %-34s %9.1f ms\n", "raw, same primitives, same GL:", t[1] * 1e3);
  std::printf("  %-34s %9.2f   (target <= 1.5)\n", "frame / raw:", t[0] / t[1]);
  std::printf("  %-34s %9.1f ms\n", "renderer frame, feathers hidden:", hidden[0] * 1e3);
  std::printf("  %-34s %9.2f\n", "(frame - hidden) / raw:", (t[0] - hidden[0]) / t[1]);
  std::printf("  %-34s %9.1f MB\n",
              "feather buffers:", static_cast<double>(buffers.byteSize()) / 1e6);
  std::printf("  %-34s %9zu bytes\n", "a feather instance:", sizeof(Feather));
  gl.DeleteBuffers(4, vertexBuffers);
  gl.DeleteVertexArrays(2, arrays);
  gl.DeleteProgram(program);
  return 0;
}
