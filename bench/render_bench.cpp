// hirsute_render_bench: the renderer's frame time against the raw throughput of the same GL.
//
// docs/design.md, "Benchmarks": frame time of a scene against the raw line and triangle throughput
// of the same GL. The scene is a seeded fan of tubes (at least a million triangles, eight
// materials, `render mode: shaded` with two lights, two-sided) and a seeded cloud of pixel-style
// line segments, one and three pixels wide. Each is drawn by GlRenderer into the headless path's
// multisampled framebuffer, then the same triangles (one vertex and one index buffer, one draw
// call) and the same segments (GL_LINES) are drawn with a trivial shader into the same framebuffer
// of the same OSMesa context. A frame is timed from the draw to glFinish; the first frame of each
// is left out, as llvmpipe compiles its shaders there, and the two are timed in turn. Figures are
// printed, never asserted.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/gl/offscreen.h"
#include "raw_gl.h"

namespace {

using hirsute::GlFunctions;
using hirsute::bench::trivialProgram;

// The renderer's frame and the raw drawing's, timed in turn (raw_gl.h).
std::pair<double, double> frameSeconds(const GlFunctions& gl, int frames,
                                       const std::function<void()>& scene,
                                       const std::function<void()>& raw) {
  const std::vector<double> t = hirsute::bench::frameSeconds(gl, frames, {scene, raw});
  return {t[0], t[1]};
}

// A fan of tubes from the origin: `tubes` tubes of `rings` rings of `sides` vertices each.
hirsute::Scene tubeScene(int tubes, int rings, int sides, std::mt19937& random) {
  hirsute::Scene scene;
  for (int i = 0; i < 9; ++i) {
    hirsute::Material m;
    float hue = static_cast<float>(i) / 8.0f;
    m.diffuse = {0.4f + 0.5f * hue, 0.7f - 0.4f * hue, 0.2f};
    m.ambient = m.diffuse * 0.2f;
    m.specular = glm::vec3(0.3f);
    m.shininess = 20;
    scene.materials.push_back(m);
  }
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int t = 0; t < tubes; ++t) {
    hirsute::TriangleMesh& mesh = scene.meshFor(1 + t % 8);
    glm::vec3 direction =
        glm::normalize(glm::vec3(unit(random), 1.5f + unit(random), unit(random)));
    glm::vec3 side = glm::normalize(glm::cross(direction, glm::vec3(0.3f, 0.1f, 1)));
    glm::vec3 other = glm::cross(direction, side);
    float length = 6 + 3 * unit(random);
    auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (int r = 0; r < rings; ++r) {
      float along = length * static_cast<float>(r) / static_cast<float>(rings - 1);
      float radius = 0.08f * (1.0f - 0.7f * along / length);
      glm::vec3 centre = direction * along + glm::vec3(0, -0.02f * along * along, 0);
      for (int s = 0; s < sides; ++s) {
        float a = glm::two_pi<float>() * static_cast<float>(s) / static_cast<float>(sides);
        glm::vec3 normal = std::cos(a) * side + std::sin(a) * other;
        mesh.positions.push_back(centre + radius * normal);
        mesh.normals.push_back(normal);
      }
    }
    for (int r = 0; r + 1 < rings; ++r) {
      for (int s = 0; s < sides; ++s) {
        std::uint32_t a = base + static_cast<std::uint32_t>(r * sides + s);
        std::uint32_t b = base + static_cast<std::uint32_t>(r * sides + (s + 1) % sides);
        std::uint32_t c = a + static_cast<std::uint32_t>(sides),
                      d = b + static_cast<std::uint32_t>(sides);
        mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
      }
    }
  }
  return scene;
}

hirsute::Scene lineScene(std::size_t count, std::mt19937& random) {
  hirsute::Scene scene;
  for (int i = 0; i < 9; ++i) {
    hirsute::Material m;
    m.diffuse = m.ambient = glm::vec3(0.2f + 0.1f * static_cast<float>(i), 0.8f, 0.3f);
    scene.materials.push_back(m);
  }
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  scene.lines.reserve(count);
  glm::vec3 p(0.0f);
  for (std::size_t i = 0; i < count; ++i) {
    // Short steps of a wandering walk, restarting now and then: hair-like strokes.
    if (i % 64 == 0) p = glm::vec3(unit(random), unit(random), unit(random)) * 5.0f;
    glm::vec3 q = p + glm::vec3(unit(random), unit(random), unit(random)) * 0.05f;
    scene.lines.push_back({p, q, 1, 1, 1 + static_cast<int>(i % 8)});
    p = q;
  }
  return scene;
}

struct RawBuffers {
  GLuint vertexArray = 0, vertices = 0, indices = 0;
  GLsizei count = 0;
};

// The raw pass keeps the z buffer (as the scene has it) and nothing else.
void rawState(const GlFunctions& gl) {
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.Disable(GL_BLEND);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void printComparison(const char* what, std::size_t primitives, double scene, double raw) {
  std::printf("  %-28s %9.1f ms   %7.2f M %s/s\n", "renderer frame:", scene * 1e3,
              static_cast<double>(primitives) / scene / 1e6, what);
  std::printf("  %-28s %9.1f ms   %7.2f M %s/s\n", "raw throughput, same GL:", raw * 1e3,
              static_cast<double>(primitives) / raw / 1e6, what);
  std::printf("  %-28s %9.2f\n", "frame / raw:", scene / raw);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Frame time of the GL renderer against the raw throughput of the same OSMesa context"};
  int tubes = 1024, rings = 33, sides = 16, frames = 5, samples = 4;
  std::size_t lineCount = 1'000'000;
  std::string size = "1024x768";
  app.add_option("--tubes", tubes,
                 "Tubes in the triangle scene (default 1024: 1,048,576 triangles)");
  app.add_option("--lines", lineCount, "Line segments in the line scene (default 1000000)");
  app.add_option("--frames", frames, "Timed frames of each (default 5; the median is printed)");
  app.add_option("--samples", samples, "Multisample antialiasing samples (default 4)");
  app.add_option("--size", size, "Image size (default 1024x768)");
  CLI11_PARSE(app, argc, argv);
  int width = std::stoi(size.substr(0, size.find('x')));
  int height = std::stoi(size.substr(size.find('x') + 1));

  std::mt19937 random(20240521);
  hirsute::Scene triangles = tubeScene(tubes, rings, sides, random);
  hirsute::Scene lines = lineScene(lineCount, random);

  hirsute::OsMesaContext context;
  const GlFunctions& gl = context.gl();
  hirsute::OffscreenFramebuffer framebuffer(gl, width, height, samples);
  framebuffer.bind();
  std::printf("GL: %s\n", context.description().c_str());
  std::printf(
      "image %dx%d, %d samples, %u hardware threads (llvmpipe uses LP_NUM_THREADS or all)\n\n",
      width, height, framebuffer.samples(), std::thread::hardware_concurrency());

  hirsute::ViewSettings view;
  view.renderMode = hirsute::RenderMode::Shaded;
  view.viewpoint = {1, 0.5f, 2};
  view.scaleFactor = 0.9f;
  for (glm::vec3 direction : {glm::vec3(1, 1, 1), glm::vec3(-1, 0.5f, 0.2f)}) {
    hirsute::LightSource light;
    light.vector = direction;
    light.ambient = glm::vec3(0.1f);
    view.lights.push_back(light);
  }
  GLuint program = trivialProgram(gl);
  GLint viewProjection = gl.GetUniformLocation(program, "uViewProjection");

  {
    hirsute::GlRenderer renderer(gl);
    auto uploadStart = std::chrono::steady_clock::now();
    renderer.upload(triangles, view, true);
    gl.Finish();
    double upload =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - uploadStart).count();
    hirsute::Camera camera = hirsute::fitCamera(view, triangles.bounds(), {width, height});

    // The same triangles as one plain buffer pair, drawn in one call.
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    for (const hirsute::TriangleMesh& mesh : triangles.meshes) {
      auto base = static_cast<std::uint32_t>(positions.size());
      positions.insert(positions.end(), mesh.positions.begin(), mesh.positions.end());
      for (std::uint32_t i : mesh.indices) indices.push_back(base + i);
    }
    RawBuffers raw;
    gl.GenVertexArrays(1, &raw.vertexArray);
    gl.BindVertexArray(raw.vertexArray);
    gl.GenBuffers(1, &raw.vertices);
    gl.BindBuffer(GL_ARRAY_BUFFER, raw.vertices);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(positions.size() * sizeof(glm::vec3)),
                  positions.data(), GL_STATIC_DRAW);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl.GenBuffers(1, &raw.indices);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, raw.indices);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                  static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(),
                  GL_STATIC_DRAW);
    raw.count = static_cast<GLsizei>(indices.size());
    auto [scene, rawTime] = frameSeconds(
        gl, frames, [&] { renderer.draw(camera); },
        [&] {
          rawState(gl);
          gl.UseProgram(program);
          gl.UniformMatrix4fv(viewProjection, 1, GL_FALSE, glm::value_ptr(camera.viewProjection()));
          gl.BindVertexArray(raw.vertexArray);
          gl.DrawElements(GL_TRIANGLES, raw.count, GL_UNSIGNED_INT, nullptr);
        });
    gl.DeleteBuffers(1, &raw.vertices);
    gl.DeleteBuffers(1, &raw.indices);
    gl.DeleteVertexArrays(1, &raw.vertexArray);

    std::printf("triangles: %zu in %zu meshes (shaded, 2 lights, two-sided, 8 materials)\n",
                renderer.triangleCount(), triangles.meshes.size());
    printComparison("triangles", renderer.triangleCount(), scene, rawTime);
    std::printf("  %-28s %9.1f ms\n\n", "upload:", upload * 1e3);
  }

  // The same segments one pixel wide (GL lines, as cpfg draws them) and three pixels wide
  // (quads: core profile has no wide lines), against raw one-pixel GL_LINES.
  for (float lineWidth : {1.0f, 3.0f}) {
    for (hirsute::LineSegment& l : lines.lines) l.widthFrom = l.widthTo = lineWidth;
    hirsute::GlRenderer renderer(gl);
    renderer.upload(lines, view, false);
    hirsute::Camera camera = hirsute::fitCamera(view, lines.bounds(), {width, height});

    std::vector<glm::vec3> ends;
    ends.reserve(lines.lines.size() * 2);
    for (const hirsute::LineSegment& l : lines.lines) {
      ends.push_back(l.from);
      ends.push_back(l.to);
    }
    RawBuffers raw;
    gl.GenVertexArrays(1, &raw.vertexArray);
    gl.BindVertexArray(raw.vertexArray);
    gl.GenBuffers(1, &raw.vertices);
    gl.BindBuffer(GL_ARRAY_BUFFER, raw.vertices);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(ends.size() * sizeof(glm::vec3)),
                  ends.data(), GL_STATIC_DRAW);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    raw.count = static_cast<GLsizei>(ends.size());
    auto [scene, rawTime] = frameSeconds(
        gl, frames, [&] { renderer.draw(camera); },
        [&] {
          rawState(gl);
          gl.UseProgram(program);
          gl.UniformMatrix4fv(viewProjection, 1, GL_FALSE, glm::value_ptr(camera.viewProjection()));
          gl.BindVertexArray(raw.vertexArray);
          gl.DrawArrays(GL_LINES, 0, raw.count);
        });
    gl.DeleteBuffers(1, &raw.vertices);
    gl.DeleteVertexArrays(1, &raw.vertexArray);

    std::printf("lines: %zu pixel-style segments %g pixel%s wide (%s), against 1-pixel GL_LINES\n",
                renderer.lineCount(), lineWidth, lineWidth > 1 ? "s" : "",
                lineWidth > 1 ? "quads of two triangles" : "GL lines");
    printComparison("segments", renderer.lineCount(), scene, rawTime);
    std::printf("\n");
  }
  gl.DeleteProgram(program);
  return 0;
}
