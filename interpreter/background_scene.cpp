// Reading cpfg's background scene files (manual §8.3) into world-space triangles and spheres.
#include "hirsute/interpreter/background_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>

#include "hirsute/lsys/preprocessor.h"
#include "hirsute/lsys/view_file_lines.h"

namespace hirsute {
namespace {

// Sides of the tessellated cylinders, cones and ellipsoids: enough that their outline stays within
// 1% of the radius (1 - cos(pi/24) < 0.009).
constexpr int kRoundSides = 24;
constexpr int kSphereStacks = 12;

struct Word {
  std::string text;
  SourceLocation where;
};

// The words of the preprocessed text, each with the user's file and line (cpp line markers).
std::vector<Word> words(const std::string& text, const std::filesystem::path& file) {
  std::vector<Word> result;
  auto name = std::make_shared<const std::string>(file.string());
  int line = 1;
  std::istringstream lines(text);
  std::string current;
  while (std::getline(lines, current)) {
    if (const auto marker = lineMarker(current)) {
      line = marker->first;
      if (!marker->second.empty() && marker->second != *name)
        name = std::make_shared<const std::string>(marker->second);
      continue;
    }
    std::istringstream split(current);
    std::string word;
    while (split >> word) result.push_back(Word{word, SourceLocation{name, line, 0}});
    ++line;
  }
  return result;
}

bool isNumber(const std::string& word, double& value) {
  const char* begin = word.c_str();
  char* end = nullptr;
  value = std::strtod(begin, &end);
  return end != begin && *end == '\0';
}

class BackgroundReader {
 public:
  explicit BackgroundReader(std::vector<Word> words) : words_(std::move(words)) {
    background_.materials.push_back(Material{});  // OpenGL's default material
  }

  BackgroundScene read() {
    while (at_ < words_.size()) {
      const Word& command = words_[at_++];
      const std::vector<double> v = numbers();
      run(command, v);
    }
    return std::move(background_);
  }

 private:
  // The numbers following a command, up to the next word that is not one.
  std::vector<double> numbers() {
    std::vector<double> values;
    double value;
    while (at_ < words_.size() && isNumber(words_[at_].text, value)) {
      values.push_back(value);
      ++at_;
    }
    return values;
  }

  [[noreturn]] static void fail(const Word& command, const std::string& message) {
    throw DiagnosticError(command.where, message);
  }

  static void expectCount(const Word& command, const std::vector<double>& v, std::size_t count) {
    if (v.size() != count) {
      fail(command, "'" + command.text + "' takes " + std::to_string(count) + " numbers, not " +
                        std::to_string(v.size()));
    }
  }

  void run(const Word& command, const std::vector<double>& v) {
    const std::string& c = command.text;
    if (c == "polygon") {
      if (v.size() < 9 || v.size() % 3 != 0)
        fail(command, "'polygon' takes 3 or more vertices of 3 numbers each");
      std::vector<glm::vec3> points;
      for (std::size_t i = 0; i < v.size(); i += 3) points.push_back(point(v, i));
      polygon(points, {});
    } else if (c == "polygonuv") {
      if (v.size() < 18 || v.size() % 6 != 0)
        fail(command, "'polygonuv' takes 3 or more vertices of 6 numbers each (x y z nx ny nz)");
      std::vector<glm::vec3> points, normals;
      for (std::size_t i = 0; i < v.size(); i += 6) {
        points.push_back(point(v, i));
        normals.push_back(point(v, i + 3));
      }
      polygon(points, normals);
    } else if (c == "rectangle") {
      expectCount(command, v, 2);
      const float a = float(v[0]), b = float(v[1]);
      polygon({{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}}, {});
    } else if (c == "mesh") {
      if (v.size() < 12 || v.size() % 6 != 0)
        fail(command, "'mesh' takes 4 + 2k vertices of 3 numbers each");
      // Manual §8.3.1: vertices 2k, 2k+1, 2k+2, 2k+3 are one rectangle; cpfg's rayshade output
      // draws it as the quad 2k, 2k+2, 2k+3, 2k+1.
      for (std::size_t k = 0; 6 * k + 12 <= v.size(); ++k) {
        const std::size_t first = 6 * k;
        polygon({point(v, first), point(v, first + 6), point(v, first + 9), point(v, first + 3)},
                {});
      }
    } else if (c == "box" || c == "prism") {
      // cpfg draws `prism a b c` as a box too (cpfg-BackgroundScene's expected.ray).
      expectCount(command, v, 3);
      box(glm::vec3(float(v[0]), float(v[1]), float(v[2])));
    } else if (c == "cone") {
      expectCount(command, v, 3);
      cylinder(float(v[0]), float(v[1]), float(v[2]));
    } else if (c == "cylinder") {
      expectCount(command, v, 2);
      cylinder(float(v[0]), float(v[0]), float(v[1]));
    } else if (c == "sphere") {
      expectCount(command, v, 1);
      sphere(float(v[0]));
    } else if (c == "material") {
      expectCount(command, v, 17);
      material(v);
    } else if (c == "loadidentity") {
      expectCount(command, v, 0);
      matrix_ = glm::mat4(1.0f);
    } else if (c == "loadmatrix") {
      expectCount(command, v, 16);
      matrix_ = columnMajor(v);
    } else if (c == "mulmatrix" || c == "multmatrix") {
      // cpfg accepts OpenGL's spelling (cpfg-BackgroundScene, enviro-CPFG-CelticKnot use it).
      expectCount(command, v, 16);
      matrix_ = matrix_ * columnMajor(v);
    } else if (c == "pushmatrix") {
      expectCount(command, v, 0);
      stack_.push_back(matrix_);
    } else if (c == "popmatrix") {
      expectCount(command, v, 0);
      if (stack_.empty()) fail(command, "'popmatrix' without a matching 'pushmatrix'");
      matrix_ = stack_.back();
      stack_.pop_back();
    } else if (c == "translate") {
      expectCount(command, v, 3);
      matrix_ = glm::translate(matrix_, point(v, 0));
    } else if (c == "rotate") {
      expectCount(command, v, 4);
      const glm::vec3 axis = point(v, 1);
      if (glm::length(axis) == 0.0f) fail(command, "'rotate' needs a non-zero axis");
      // glRotate: angle in degrees about the normalised axis.
      matrix_ = glm::rotate(matrix_, glm::radians(float(v[0])), glm::normalize(axis));
    } else if (c == "scale") {
      expectCount(command, v, 3);
      matrix_ = glm::scale(matrix_, point(v, 0));
    } else if (c == "clear" || c == "light" || c == "ortho" || c == "perspective" ||
               c == "lookat" || c == "matrixmode") {
      // Manual §8.3.4: written by -gls for its own viewer, not needed in a background file; the
      // view file gives the lights and the projection.
    } else {
      fail(command, "unknown background scene command '" + c + "'");
    }
  }

  static glm::vec3 point(const std::vector<double>& v, std::size_t i) {
    return glm::vec3(float(v[i]), float(v[i + 1]), float(v[i + 2]));
  }

  static glm::mat4 columnMajor(const std::vector<double>& v) {
    // Manual §8.3.3: a1-a4 are the first column (OpenGL order, as glm stores it).
    float values[16];
    for (int i = 0; i < 16; ++i) values[i] = float(v[static_cast<std::size_t>(i)]);
    return glm::make_mat4(values);
  }

  void material(const std::vector<double>& v) {
    // Manual §8.3.2: ambient, diffuse, specular, emission (RGBA each), then the exponent. The
    // diffuse alpha is the opacity, as in cpfg's rayshade output (transp = 1 - alpha).
    Material m;
    m.ambient = point(v, 0);
    m.diffuse = point(v, 4);
    m.specular = point(v, 8);
    m.emission = point(v, 12);
    m.transparency = std::clamp(1.0f - float(v[7]), 0.0f, 1.0f);
    m.shininess = std::clamp(float(v[16]), 0.0f, 128.0f);
    background_.materials.push_back(m);
    currentMaterial_ = static_cast<int>(background_.materials.size()) - 1;
  }

  TriangleMesh& mesh() {
    if (background_.meshes.empty() || background_.meshes.back().material != currentMaterial_) {
      background_.meshes.emplace_back();
      background_.meshes.back().material = currentMaterial_;
    }
    return background_.meshes.back();
  }

  glm::vec3 transformPoint(const glm::vec3& p) const {
    return glm::vec3(matrix_ * glm::vec4(p, 1));
  }

  glm::vec3 transformNormal(const glm::vec3& n) const {
    const glm::vec3 world = glm::transpose(glm::inverse(glm::mat3(matrix_))) * n;
    const float length = glm::length(world);
    return length > 0 ? world / length : glm::vec3(0, 0, 1);
  }

  // A convex polygon in local coordinates, as a triangle fan from its first vertex (cpfg's
  // rayshade output). Without normals, the face's normal from its first three vertices.
  void polygon(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals) {
    std::vector<glm::vec3> world;
    for (const glm::vec3& p : points) world.push_back(transformPoint(p));
    glm::vec3 face = glm::cross(world[1] - world[0], world[2] - world[0]);
    face = glm::length(face) > 0 ? glm::normalize(face) : glm::vec3(0, 0, 1);
    TriangleMesh& m = mesh();
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (std::size_t i = 0; i < world.size(); ++i) {
      m.positions.push_back(world[i]);
      m.normals.push_back(normals.empty() ? face : transformNormal(normals[i]));
    }
    for (std::uint32_t i = 1; i + 1 < world.size(); ++i) {
      m.indices.insert(m.indices.end(), {base, base + i, base + i + 1});
      ++background_.counts.triangles;
    }
  }

  void box(const glm::vec3& size) {
    const float a = size.x, b = size.y, c = size.z;
    // Six faces, counter-clockwise seen from outside.
    polygon({{0, 0, 0}, {0, b, 0}, {a, b, 0}, {a, 0, 0}}, {});  // z = 0
    polygon({{0, 0, c}, {a, 0, c}, {a, b, c}, {0, b, c}}, {});  // z = c
    polygon({{0, 0, 0}, {a, 0, 0}, {a, 0, c}, {0, 0, c}}, {});  // y = 0
    polygon({{0, b, 0}, {0, b, c}, {a, b, c}, {a, b, 0}}, {});  // y = b
    polygon({{0, 0, 0}, {0, 0, c}, {0, b, c}, {0, b, 0}}, {});  // x = 0
    polygon({{a, 0, 0}, {a, b, 0}, {a, b, c}, {a, 0, c}}, {});  // x = a
  }

  // A cone (or cylinder) along the local y axis from radius r1 at y = 0 to r2 at y = h, closed by
  // a disc at each end of non-zero radius (as cpfg's rayshade output writes them).
  void cylinder(float r1, float r2, float h) {
    TriangleMesh& m = mesh();
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    const float slope = h != 0 ? (r1 - r2) / h : 0.0f;
    for (int i = 0; i <= kRoundSides; ++i) {
      const float angle = 2.0f * float(M_PI) * float(i) / float(kRoundSides);
      const glm::vec3 out(std::cos(angle), 0, -std::sin(angle));
      const glm::vec3 normal = transformNormal(glm::vec3(out.x, slope, out.z));
      m.positions.push_back(transformPoint(out * r1));
      m.normals.push_back(normal);
      m.positions.push_back(transformPoint(out * r2 + glm::vec3(0, h, 0)));
      m.normals.push_back(normal);
    }
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(kRoundSides); ++i) {
      const std::uint32_t a = base + 2 * i, b = a + 1, c = a + 2, d = a + 3;
      m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
    }
    ++background_.counts.cylinders;
    cap(r1, 0.0f, -1.0f);
    cap(r2, h, 1.0f);
  }

  void cap(float radius, float y, float facing) {
    if (radius <= 0) return;
    TriangleMesh& m = mesh();
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    const glm::vec3 normal = transformNormal(glm::vec3(0, facing, 0));
    m.positions.push_back(transformPoint(glm::vec3(0, y, 0)));
    m.normals.push_back(normal);
    for (int i = 0; i < kRoundSides; ++i) {
      const float angle = 2.0f * float(M_PI) * float(i) / float(kRoundSides);
      m.positions.push_back(
          transformPoint(glm::vec3(radius * std::cos(angle), y, -radius * std::sin(angle))));
      m.normals.push_back(normal);
    }
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(kRoundSides); ++i) {
      const std::uint32_t a = base + 1 + i, b = base + 1 + (i + 1) % kRoundSides;
      if (facing > 0)
        m.indices.insert(m.indices.end(), {base, a, b});
      else
        m.indices.insert(m.indices.end(), {base, b, a});
    }
    ++background_.counts.discs;
  }

  // A sphere stays a Scene sphere when the matrix keeps its shape (rotation and uniform scale);
  // otherwise (as `scale 2 1 1` in cpfg-BackgroundScene) it is tessellated as the ellipsoid
  // OpenGL draws.
  void sphere(float radius) {
    ++background_.counts.spheres;
    const glm::mat3 linear(matrix_);
    const float sx = glm::length(linear[0]), sy = glm::length(linear[1]),
                sz = glm::length(linear[2]);
    const float tolerance = 1e-5f * std::max({sx, sy, sz, 1e-30f});
    const bool orthogonal = std::abs(glm::dot(linear[0], linear[1])) <= tolerance * sx &&
                            std::abs(glm::dot(linear[0], linear[2])) <= tolerance * sx &&
                            std::abs(glm::dot(linear[1], linear[2])) <= tolerance * sy;
    if (orthogonal && std::abs(sx - sy) <= tolerance && std::abs(sx - sz) <= tolerance) {
      background_.spheres.push_back(
          Sphere{transformPoint(glm::vec3(0)), radius * sx, currentMaterial_});
      return;
    }
    TriangleMesh& m = mesh();
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int stack = 0; stack <= kSphereStacks; ++stack) {
      const float polar = float(M_PI) * float(stack) / float(kSphereStacks);
      for (int i = 0; i <= kRoundSides; ++i) {
        const float angle = 2.0f * float(M_PI) * float(i) / float(kRoundSides);
        const glm::vec3 unit(std::sin(polar) * std::cos(angle), std::cos(polar),
                             -std::sin(polar) * std::sin(angle));
        m.positions.push_back(transformPoint(unit * radius));
        m.normals.push_back(transformNormal(unit));
      }
    }
    const auto row = static_cast<std::uint32_t>(kRoundSides + 1);
    for (std::uint32_t stack = 0; stack < static_cast<std::uint32_t>(kSphereStacks); ++stack) {
      for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(kRoundSides); ++i) {
        const std::uint32_t a = base + stack * row + i, b = a + 1, c = a + row, d = c + 1;
        m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
      }
    }
  }

  std::vector<Word> words_;
  std::size_t at_ = 0;
  BackgroundScene background_;
  glm::mat4 matrix_{1.0f};
  std::vector<glm::mat4> stack_;
  int currentMaterial_ = 0;
};

}  // namespace

BackgroundScene loadBackgroundScene(const std::filesystem::path& file, Diagnostics& diagnostics,
                                    const PreprocessorOptions& preprocessing) {
  // Manual §8.3.5: "The file is preprocessed by cpfg, and therefore macros and comments are
  // allowed."
  const std::string text = preprocessFile(file, preprocessing, diagnostics);
  return BackgroundReader(words(text, file)).read();
}

void appendBackgroundScene(const BackgroundScene& background, Scene& scene) {
  const int first = static_cast<int>(scene.materials.size());
  scene.materials.insert(scene.materials.end(), background.materials.begin(),
                         background.materials.end());
  for (TriangleMesh mesh : background.meshes) {
    mesh.material += first;
    scene.meshes.push_back(std::move(mesh));
  }
  for (Sphere sphere : background.spheres) {
    sphere.material += first;
    scene.spheres.push_back(sphere);
  }
}

}  // namespace hirsute
