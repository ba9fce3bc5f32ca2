// The shells' frame time (Silva et al. 2010, Table 1) against the raw throughput of the same GL:
// the paper's furry torus (models/fur-torus) at its triangle count and at the counts of the
// paper's other models (a torus of as many triangles: 20 845 to 365 118), 16 and 64 layers, at
// 800×600 and 1680×1050, each beside the same triangles drawn as many times with a trivial shader
// (bench/raw_gl.h) in the same OSMesa context. The torus of each count is the model's L-system
// with more segments around the ring (36 sides, 5 strips a segment: 360 triangles a segment);
// beside the tori, a pear mesh of each count read from an OBJ (docs/meshes.md), the same fur on it.
#include <cmath>
#include <CLI/CLI.hpp>
#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/gtc/type_ptr.hpp>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/gl/offscreen.h"
#include "model_pipeline.h"
#include "raw_gl.h"

namespace fs = std::filesystem;

namespace {

std::string readText(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A closed body of revolution with a texture atlas, as an OBJ of about `count` triangles: a pear
// (the paper's second model) along y, `rings` rings of twice as many sides, fans at the poles.
std::string pearObj(int count) {
  const int rings = std::max(4, static_cast<int>(std::lround(std::sqrt(count / 4.0))));
  const int sides = 2 * rings;
  const double pi = std::acos(-1.0);
  std::ostringstream obj;
  obj.precision(7);
  for (int i = 1; i < rings; ++i) {
    const double t = static_cast<double>(i) / rings;
    const double radius = 0.9 * std::pow(std::sin(pi * t), 0.6) * (1.0 - 0.45 * t);
    for (int j = 0; j <= sides; ++j) {
      const double a = 2 * pi * j / sides;
      obj << "v " << radius * std::cos(a) << ' ' << 3.0 * t << ' ' << -radius * std::sin(a)
          << "\nvt " << static_cast<double>(j) / sides << ' ' << t << '\n';
    }
  }
  obj << "v 0 0 0\nvt 0.5 0\nv 0 3 0\nvt 0.5 1\n";
  const int ring = sides + 1, bottom = (rings - 1) * ring + 1, top = bottom + 1;
  const auto at = [&](int i, int j) { return (i - 1) * ring + j + 1; };
  for (int i = 1; i + 1 < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const int a = at(i, j), b = at(i, j + 1), c = at(i + 1, j), d = at(i + 1, j + 1);
      obj << "f " << a << '/' << a << ' ' << b << '/' << b << ' ' << d << '/' << d << '\n'
          << "f " << a << '/' << a << ' ' << d << '/' << d << ' ' << c << '/' << c << '\n';
    }
  }
  for (int j = 0; j < sides; ++j) {
    obj << "f " << bottom << '/' << bottom << ' ' << at(1, j + 1) << '/' << at(1, j + 1) << ' '
        << at(1, j) << '/' << at(1, j) << '\n';
    obj << "f " << top << '/' << top << ' ' << at(rings - 1, j) << '/' << at(rings - 1, j) << ' '
        << at(rings - 1, j + 1) << '/' << at(rings - 1, j + 1) << '\n';
  }
  return obj.str();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hirsute;
  int frames = 5;
  std::vector<int> counts{9360, 20845, 44452, 92689, 95533, 142307, 154789, 365118};
  std::vector<int> layers{16, 64};
  std::vector<std::string> sizes{"800x600", "1680x1050"};
  CLI::App app{"Frame time of shell fur on tori of the paper's triangle counts against raw GL"};
  app.add_option("--frames", frames, "Timed frames of each (default 5; the median is printed)");
  app.add_option("--triangles", counts, "Triangle counts of the tori (default: the paper's)");
  app.add_option("--layers", layers, "Layer counts (default 16 64)");
  app.add_option("--sizes", sizes, "Image sizes (default 800x600 1680x1050)");
  std::vector<std::string> surfaces{"torus", "mesh"};
  app.add_option("--surfaces", surfaces,
                 "torus: the model's torus of each count; mesh: a pear mesh of each count read "
                 "from an OBJ (docs/meshes.md) (default both)")
      ->check(CLI::IsMember({"torus", "mesh"}));
  CLI11_PARSE(app, argc, argv);

  const fs::path model = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "fur-torus";
  const std::string lsystem = readText(model / "torus.l"), view = readText(model / "torus.v");
  const fs::path work = fs::temp_directory_path() / ("hirsute_fur_bench_" + std::to_string(::getpid()));
  fs::create_directories(work);

  OsMesaContext context;
  const GlFunctions& gl = context.gl();
  std::printf("GL: %s\n", context.description().c_str());
  std::printf("%7s %9s %7s %10s %12s %10s %10s %8s\n", "surface", "triangles", "layers", "image",
              "frame ms", "fps", "raw ms", "ratio");
  const GLuint raw = bench::trivialProgram(gl);
  for (const std::string& surface : surfaces) {
  for (int count : counts) {
    const int segments = std::max(3, static_cast<int>(std::lround(count / 360.0)));
    for (int n : layers) {
      if (surface == "torus") {
        std::ofstream(work / "torus.l") << std::regex_replace(
            lsystem, std::regex(R"(#define N 26)"), "#define N " + std::to_string(segments));
        std::ofstream(work / "torus.v") << std::regex_replace(
            view, std::regex(R"(fur layers: 16)"), "fur layers: " + std::to_string(n));
      } else {
        // The torus's fur on a mesh surface: the same modules before ~B, the same view lines.
        std::ofstream(work / "pear.obj") << pearObj(count);
        std::ofstream(work / "torus.l")
            << "Lsystem: 1\nderivation length: 0\nAxiom: ;(1) @Uf(1) @Ul(0.35) @Ud(0.45) "
               "@Us(30, 1) @Uh(0.25, 30, 2) ~B(1)\nendlsystem\n";
        std::ofstream(work / "torus.v")
            << std::regex_replace(view, std::regex(R"(fur layers: 16)"),
                                  "fur layers: " + std::to_string(n))
            << "\nsurface: B pear.obj 1\n";
      }
      cli::ModelOptions options;
      options.lsystemFile = (work / "torus.l").string();
      options.viewFile = (work / "torus.v").string();
      options.colormaps = {(model / "torus.map").string()};
      Diagnostics diagnostics(&std::cerr);
      cli::BuiltScene built;
      try {
        built = cli::buildScene(options, diagnostics);
      } catch (const DiagnosticError& e) {
        std::cerr << e.diagnostic().text() << '\n';
        return 2;
      }
      const Scene& scene = built.scene;
      const FurSurface& fur = scene.organ<FurPart>().surfaces.at(0);
      for (const std::string& size : sizes) {
        const int width = std::stoi(size.substr(0, size.find('x')));
        const int height = std::stoi(size.substr(size.find('x') + 1));
        OffscreenFramebuffer framebuffer(gl, width, height, 1);
        framebuffer.bind();
        GlRenderer renderer(gl);
        renderer.upload(scene, built.resources.view, built.resources.materialMode);
        const Camera camera = fitCamera(built.resources.view, scene.bounds(), {width, height});
        // The raw baseline: the surface once and its triangles n times more, trivially shaded.
        GLuint array = 0, buffers[2] = {};
        gl.GenVertexArrays(1, &array);
        gl.GenBuffers(2, buffers);
        gl.BindVertexArray(array);
        gl.BindBuffer(GL_ARRAY_BUFFER, buffers[0]);
        gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(fur.positions.size() * sizeof(glm::vec3)),
                      fur.positions.data(), GL_STATIC_DRAW);
        gl.EnableVertexAttribArray(0);
        gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
        gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);
        gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                      static_cast<GLsizeiptr>(fur.indices.size() * sizeof(std::uint32_t)),
                      fur.indices.data(), GL_STATIC_DRAW);
        gl.BindVertexArray(0);
        const GLint viewProjection = gl.GetUniformLocation(raw, "uViewProjection");
        auto drawScene = [&] { renderer.draw(camera); };
        auto drawRaw = [&] {
          gl.Enable(GL_DEPTH_TEST);
          gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
          gl.UseProgram(raw);
          gl.UniformMatrix4fv(viewProjection, 1, GL_FALSE, glm::value_ptr(camera.viewProjection()));
          gl.BindVertexArray(array);
          gl.DrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(fur.indices.size()),
                                   GL_UNSIGNED_INT, nullptr, n + 1);
        };
        const std::vector<double> t = bench::frameSeconds(gl, frames, {drawScene, drawRaw});
        std::printf("%7s %9zu %7d %10s %12.1f %10.1f %10.1f %8.2f\n", surface.c_str(),
                    fur.triangleCount(), n, size.c_str(), t[0] * 1e3, 1.0 / t[0], t[1] * 1e3,
                    t[0] / t[1]);
        std::fflush(stdout);
        gl.DeleteBuffers(2, buffers);
        gl.DeleteVertexArrays(1, &array);
      }
    }
  }
  }
  gl.DeleteProgram(raw);
  fs::remove_all(work);
  return 0;
}
