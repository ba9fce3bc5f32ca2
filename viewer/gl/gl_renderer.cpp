#include "hirsute/viewer/gl/gl_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>

#include "hirsute/viewer/gl/gl_objects.h"
#include "hirsute/viewer/gl/gl_shaders.h"
#include "hirsute/viewer/gl/organ_drawing.h"
#include "label_overlay.h"

namespace hirsute {

using gl::checkErrors;
using gl::floatAttribute;
using gl::intAttribute;
using gl::linkProgram;
using gl::makeBuffer;

struct GlRenderer::Program {
  GLuint id = 0;
  GLint material = -1, twoSided = -1;

  GLint uniform(const GlFunctions& gl, const char* name) const {
    return gl.GetUniformLocation(id, name);
  }
};

// An indexed triangle set in GL buffers: a scene mesh, or the unit sphere or disc that the
// instances of spheres and discs share.
struct GlRenderer::Mesh {
  GLuint vertexArray = 0;
  GLuint buffers[4] = {0, 0, 0, 0};  // positions, normals, texcoords, indices
  GLsizei indexCount = 0;
  int material = 0;
  int texture = -1;
  bool twoSided = true;
  bool transparent = false;
  bool normals = false;
};

struct GlRenderer::Resources {
  std::map<int, Program> surfacePrograms;  // by surfaceProgramKey
  Program thinLineProgram, wideLineProgram;
  std::vector<std::unique_ptr<OrganDrawing>> organs;  // one a type of organDrawings()
  GLuint materialBuffer = 0, materialTexture = 0;
  int materialCount = 0;
  std::vector<Mesh> meshes;
  std::vector<GLuint> textures;
  Mesh unitSphere, unitDisc;
  GLuint sphereInstances = 0, discInstances = 0;
  GLuint lineBuffer = 0, lineTexture = 0, lineArray = 0;  // the segments as a buffer texture
  GLsizei sphereCount = 0, discCount = 0;
  GLsizei thinLineCount = 0, wideLineCount = 0;  // thin ones first in the buffer
  // What upload() keeps of the view.
  RenderMode renderMode = RenderMode::Filled;
  bool zBuffer = true;
  ViewLighting lighting;        // view_lighting.h: the rule the exporters share
  bool anyTransparent = false;  // blending costs, so only a palette with transparency gets it
  LineStyle lineStyle = LineStyle::Pixel;
  glm::vec3 background{0.0f};
  std::unique_ptr<LabelOverlay> labels;  // @L text, drawn over the image
};

namespace {

// Texture units: 0 a mesh's texture, 1 the materials, 2 the line segments.
constexpr int kMaterialUnit = 1;
constexpr int kLineUnit = 2;

// Positions (attribute 0, `components` floats each), optional normals and texcoords
// (attributes 1, 2) and triangle indices, in a new vertex array that stays bound.
void uploadMesh(const GlFunctions& gl, GLuint& vertexArray, GLuint* buffers, const float* positions,
                std::size_t vertexCount, int components, const std::vector<glm::vec3>* normals,
                const std::vector<glm::vec2>* texcoords,
                const std::vector<std::uint32_t>& indices) {
  gl.GenVertexArrays(1, &vertexArray);
  gl.BindVertexArray(vertexArray);
  gl.GenBuffers(1, &buffers[0]);
  gl.BindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  auto bytes = vertexCount * static_cast<std::size_t>(components) * sizeof(float);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes), positions, GL_STATIC_DRAW);
  floatAttribute(gl, 0, components, 0, 0, false);
  if (normals && normals->size() == vertexCount) {
    buffers[1] = makeBuffer(gl, GL_ARRAY_BUFFER, *normals);
    floatAttribute(gl, 1, 3, 0, 0, false);
  }
  if (texcoords && texcoords->size() == vertexCount) {
    buffers[2] = makeBuffer(gl, GL_ARRAY_BUFFER, *texcoords);
    floatAttribute(gl, 2, 2, 0, 0, false);
  }
  buffers[3] = makeBuffer(gl, GL_ELEMENT_ARRAY_BUFFER, indices);
}

// A unit sphere of `sides` around and sides/2 from pole to pole, with triangle fans at the poles.
void unitSphere(int sides, std::vector<glm::vec3>& positions, std::vector<std::uint32_t>& indices) {
  int stacks = std::max(2, sides / 2);
  positions.push_back({0, 1, 0});
  for (int i = 1; i < stacks; ++i) {
    float polar = glm::pi<float>() * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j < sides; ++j) {
      float azimuth = glm::two_pi<float>() * static_cast<float>(j) / static_cast<float>(sides);
      positions.push_back({std::sin(polar) * std::cos(azimuth), std::cos(polar),
                           -std::sin(polar) * std::sin(azimuth)});
    }
  }
  positions.push_back({0, -1, 0});
  auto ring = [&](int i, int j) {
    return static_cast<std::uint32_t>(1 + (i - 1) * sides + (j % sides));
  };
  auto bottom = static_cast<std::uint32_t>(positions.size() - 1);
  for (int j = 0; j < sides; ++j) {
    indices.insert(indices.end(), {0u, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < stacks; ++i) {
      indices.insert(indices.end(), {ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      indices.insert(indices.end(), {ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
    indices.insert(indices.end(), {ring(stacks - 1, j), bottom, ring(stacks - 1, j + 1)});
  }
}

// A unit disc of `sides` in the xy plane, counter-clockwise seen from +z.
void unitDisc(int sides, std::vector<glm::vec2>& positions, std::vector<std::uint32_t>& indices) {
  positions.push_back({0, 0});
  for (int j = 0; j < sides; ++j) {
    float a = glm::two_pi<float>() * static_cast<float>(j) / static_cast<float>(sides);
    positions.push_back({std::cos(a), std::sin(a)});
  }
  for (int j = 0; j < sides; ++j) {
    indices.insert(indices.end(), {0u, static_cast<std::uint32_t>(1 + j),
                                   static_cast<std::uint32_t>(1 + (j + 1) % sides)});
  }
}

enum class Geometry { Mesh, Sphere, Disc };

int surfaceProgramKey(Geometry geometry, int shading, bool textured) {
  return static_cast<int>(geometry) * 100 + shading * 10 + (textured ? 1 : 0);
}

int shadingOf(RenderMode mode) {
  switch (mode) {
    case RenderMode::Flat:
      return 1;
    case RenderMode::Shaded:
    case RenderMode::Shadows:
      return 2;
    default:
      return 0;  // wireframe, filled, interpolated, fast: cpfg draws the colour itself
  }
}

}  // namespace

int sphereSides(int contourSides) {
  int sides = 4;
  while (sides < contourSides && sides < 1024) sides *= 2;
  return sides;
}

GlRenderer::GlRenderer(const GlFunctions& gl)
    : gl_(gl), resources_(std::make_unique<Resources>()), hidden_(organDrawings().size(), false) {
  Resources& r = *resources_;
  try {
    r.thinLineProgram.id = linkProgram(gl_,
                                       {shaders::kVersion, shaders::kMaterialAndLighting,
                                        shaders::kLineVertexCommon, shaders::kThinLineVertexMain},
                                       {shaders::kVersion, shaders::kLineFragmentMain});
    r.wideLineProgram.id = linkProgram(gl_,
                                       {shaders::kVersion, shaders::kMaterialAndLighting,
                                        shaders::kLineVertexCommon, shaders::kWideLineVertexMain},
                                       {shaders::kVersion, shaders::kLineFragmentMain});
    for (const OrganDrawingType* type : organDrawings()) r.organs.push_back(type->make(gl_));
    // The other programs are built on first use; building the plainest now finds a context
    // that cannot compile them at once.
    surfaceProgram(static_cast<int>(Geometry::Mesh), 0, false);
    r.labels = std::make_unique<LabelOverlay>(gl_);
  } catch (...) {
    for (Program* p : {&r.thinLineProgram, &r.wideLineProgram}) {
      if (p->id) gl_.DeleteProgram(p->id);
    }
    throw;
  }
}

GlRenderer::~GlRenderer() {
  release();
  gl_.DeleteProgram(resources_->thinLineProgram.id);
  gl_.DeleteProgram(resources_->wideLineProgram.id);
  resources_->organs.clear();
  for (auto& [key, program] : resources_->surfacePrograms) gl_.DeleteProgram(program.id);
}

const GlRenderer::Program& GlRenderer::surfaceProgram(int geometry, int shading, bool textured) {
  int key = surfaceProgramKey(static_cast<Geometry>(geometry), shading, textured);
  auto found = resources_->surfacePrograms.find(key);
  if (found != resources_->surfacePrograms.end()) return found->second;
  std::string defines = "#define SHADING " + std::to_string(shading) + "\n#define TEXTURED " +
                        (textured ? "1" : "0") + "\n";
  const char* main = geometry == static_cast<int>(Geometry::Sphere) ? shaders::kSphereVertexMain
                     : geometry == static_cast<int>(Geometry::Disc) ? shaders::kDiscVertexMain
                                                                    : shaders::kMeshVertexMain;
  Program p;
  p.id = linkProgram(gl_,
                     {shaders::kVersion, defines.c_str(), shaders::kMaterialAndLighting,
                      shaders::kSurfaceVertexOutput, main},
                     {shaders::kVersion, defines.c_str(), shaders::kMaterialAndLighting,
                      shaders::kSurfaceFragmentMain});
  p.material = gl_.GetUniformLocation(p.id, "uMaterial");
  p.twoSided = gl_.GetUniformLocation(p.id, "uTwoSided");
  return resources_->surfacePrograms.emplace(key, p).first->second;
}

void GlRenderer::release() {
  Resources& r = *resources_;
  auto releaseMesh = [&](Mesh& m) {
    if (m.vertexArray) gl_.DeleteVertexArrays(1, &m.vertexArray);
    m.vertexArray = 0;
    for (GLuint& b : m.buffers) {
      if (b) gl_.DeleteBuffers(1, &b);
      b = 0;
    }
  };
  for (Mesh& m : r.meshes) releaseMesh(m);
  r.meshes.clear();
  releaseMesh(r.unitSphere);
  releaseMesh(r.unitDisc);
  if (r.lineArray) gl_.DeleteVertexArrays(1, &r.lineArray);
  r.lineArray = 0;
  for (const auto& organ : r.organs) organ->release();
  for (GLuint* b : {&r.sphereInstances, &r.discInstances, &r.lineBuffer, &r.materialBuffer}) {
    if (*b) gl_.DeleteBuffers(1, b);
    *b = 0;
  }
  for (GLuint* t : {&r.materialTexture, &r.lineTexture}) {
    if (*t) gl_.DeleteTextures(1, t);
    *t = 0;
  }
  for (GLuint t : r.textures) {
    if (t) gl_.DeleteTextures(1, &t);
  }
  r.textures.clear();
  r.sphereCount = r.discCount = r.thinLineCount = r.wideLineCount = 0;
  triangles_ = lines_ = 0;
}

void GlRenderer::setDetail(float fraction) {
  detail_ = std::isnan(fraction) ? 1.0f : std::clamp(fraction, 0.0f, 1.0f);
}

std::size_t GlRenderer::organIndex(std::string_view organ) const {
  const std::span<const OrganDrawingType* const> types = organDrawings();
  for (std::size_t k = 0; k < types.size(); ++k) {
    if (organ == types[k]->name()) return k;
  }
  throw std::invalid_argument("no organ draws as '" + std::string(organ) + "'");
}

void GlRenderer::setOrganVisible(std::string_view organ, bool visible) {
  hidden_[organIndex(organ)] = !visible;
}

bool GlRenderer::organVisible(std::string_view organ) const {
  return !hidden_[organIndex(organ)];
}

void GlRenderer::updateOrgan(std::string_view organ, const Scene& scene) {
  resources_->organs[organIndex(organ)]->update(scene, resources_->textures);
  checkErrors(gl_, "organ update");
}

std::size_t GlRenderer::organInstances(std::string_view organ) const {
  return resources_->organs[organIndex(organ)]->instances();
}

std::size_t GlRenderer::organPrimitives(std::string_view organ) const {
  return resources_->organs[organIndex(organ)]->primitives();
}

bool GlRenderer::organThins(std::string_view organ) const {
  return resources_->organs[organIndex(organ)]->thins();
}

std::size_t GlRenderer::thinnedInstances() const {
  std::size_t n = 0;
  for (const auto& organ : resources_->organs) {
    if (organ->thins()) n += organ->instances();
  }
  return n;
}

void GlRenderer::upload(const Scene& scene, const ViewSettings& view, bool materialMode) {
  release();
  Resources& r = *resources_;
  r.renderMode = view.renderMode;
  r.zBuffer = view.zBuffer;
  r.lineStyle = scene.lineStyle;
  // The default light's direction follows the camera: draw() places it.
  r.lighting = viewLighting(view, materialMode, glm::vec3(0, 0, 1));
  if (r.lighting.lights.size() > kMaxLights) r.lighting.lights.resize(kMaxLights);
  r.background = backgroundColor(scene, materialMode);
  r.labels->upload(scene);

  // Materials: a texture buffer of four RGBA32F texels each, which every shader indexes.
  std::vector<Material> palette = scene.materials;
  if (palette.empty()) palette.emplace_back();
  std::vector<glm::vec4> materials;
  materials.reserve(palette.size() * 4);
  r.anyTransparent = false;
  for (const Material& m : palette) {
    r.anyTransparent = r.anyTransparent || m.transparency > 0;
    materials.emplace_back(m.ambient, 1.0f - m.transparency);
    materials.emplace_back(m.diffuse, m.shininess);
    materials.emplace_back(m.specular, 0.0f);
    materials.emplace_back(m.emission, 0.0f);
  }
  r.materialCount = static_cast<int>(palette.size());
  r.materialBuffer = makeBuffer(gl_, GL_TEXTURE_BUFFER, materials);
  gl_.GenTextures(1, &r.materialTexture);
  gl_.BindTexture(GL_TEXTURE_BUFFER, r.materialTexture);
  gl_.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, r.materialBuffer);

  // Textures, turned so that t = 0 is the image's bottom row, as GL reads texture coordinates.
  for (const Texture& t : scene.textures) {
    std::size_t row = static_cast<std::size_t>(std::max(t.width, 0)) * 4;
    if (t.width <= 0 || t.height <= 0 || t.rgba.size() < row * static_cast<std::size_t>(t.height)) {
      r.textures.push_back(0);  // a texture without pixels leaves its meshes untextured
      continue;
    }
    GLuint id = 0;
    gl_.GenTextures(1, &id);
    r.textures.push_back(id);
    std::vector<std::uint8_t> flipped(row * static_cast<std::size_t>(t.height));
    for (int y = 0; y < t.height; ++y) {
      std::copy_n(&t.rgba[static_cast<std::size_t>(t.height - 1 - y) * row], row,
                  &flipped[static_cast<std::size_t>(y) * row]);
    }
    gl_.BindTexture(GL_TEXTURE_2D, id);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t.width, t.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                   flipped.data());
    gl_.GenerateMipmap(GL_TEXTURE_2D);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  }

  for (const TriangleMesh& source : scene.meshes) {
    if (source.indices.size() < 3 || source.positions.empty()) continue;
    Mesh mesh;
    mesh.indexCount = static_cast<GLsizei>(source.indices.size() / 3 * 3);
    mesh.material = source.material;
    bool textured = source.texture >= 0 && source.texture < static_cast<int>(r.textures.size()) &&
                    r.textures[static_cast<std::size_t>(source.texture)] != 0 &&
                    source.texcoords.size() == source.positions.size();
    mesh.texture = textured ? source.texture : -1;
    mesh.twoSided = source.twoSided;
    int m = std::clamp(source.material, 0, r.materialCount - 1);
    mesh.transparent = palette[static_cast<std::size_t>(m)].transparency > 0;
    mesh.normals = source.normals.size() == source.positions.size();
    uploadMesh(gl_, mesh.vertexArray, mesh.buffers, &source.positions.front().x,
               source.positions.size(), 3, &source.normals, textured ? &source.texcoords : nullptr,
               source.indices);
    triangles_ += source.indices.size() / 3;
    r.meshes.push_back(mesh);
  }
  // Transparent meshes last, so that they blend over everything opaque.
  std::stable_partition(r.meshes.begin(), r.meshes.end(),
                        [](const Mesh& m) { return !m.transparent; });

  int sides = std::max(3, view.contourSides);
  if (!scene.spheres.empty()) {
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    unitSphere(sphereSides(sides), positions, indices);
    uploadMesh(gl_, r.unitSphere.vertexArray, r.unitSphere.buffers, &positions.front().x,
               positions.size(), 3, nullptr, nullptr, indices);
    r.unitSphere.indexCount = static_cast<GLsizei>(indices.size());
    r.sphereInstances = makeBuffer(gl_, GL_ARRAY_BUFFER, scene.spheres);
    constexpr auto stride = static_cast<GLsizei>(sizeof(Sphere));
    floatAttribute(gl_, 3, 3, stride, offsetof(Sphere, center), true);
    floatAttribute(gl_, 4, 1, stride, offsetof(Sphere, radius), true);
    intAttribute(gl_, 5, stride, offsetof(Sphere, material));
    r.sphereCount = static_cast<GLsizei>(scene.spheres.size());
    triangles_ += indices.size() / 3 * scene.spheres.size();
  }
  if (!scene.discs.empty()) {
    std::vector<glm::vec2> positions;
    std::vector<std::uint32_t> indices;
    unitDisc(sides, positions, indices);
    uploadMesh(gl_, r.unitDisc.vertexArray, r.unitDisc.buffers, &positions.front().x,
               positions.size(), 2, nullptr, nullptr, indices);
    r.unitDisc.indexCount = static_cast<GLsizei>(indices.size());
    r.discInstances = makeBuffer(gl_, GL_ARRAY_BUFFER, scene.discs);
    constexpr auto stride = static_cast<GLsizei>(sizeof(Disc));
    floatAttribute(gl_, 3, 3, stride, offsetof(Disc, center), true);
    floatAttribute(gl_, 4, 3, stride, offsetof(Disc, normal), true);
    floatAttribute(gl_, 5, 1, stride, offsetof(Disc, radius), true);
    intAttribute(gl_, 6, stride, offsetof(Disc, material));
    r.discCount = static_cast<GLsizei>(scene.discs.size());
    triangles_ += indices.size() / 3 * scene.discs.size();
  }
  if (!scene.lines.empty()) {
    // The segments go up as the Scene holds them, the thin ones first; the line shaders read
    // them as floats.
    static_assert(sizeof(LineSegment) == 9 * sizeof(float), "the line shaders read 9 floats");
    GLint maxTexels = 0;
    gl_.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    if (scene.lines.size() * 9 > static_cast<std::size_t>(maxTexels)) {
      throw std::runtime_error("GL cannot hold " + std::to_string(scene.lines.size()) +
                               " line segments (at most " + std::to_string(maxTexels / 9) + ")");
    }
    auto thin = [&](const LineSegment& l) {
      return scene.lineStyle == LineStyle::Pixel && l.widthFrom <= 1 && l.widthTo <= 1;
    };
    auto thinCount =
        static_cast<std::size_t>(std::count_if(scene.lines.begin(), scene.lines.end(), thin));
    if (thinCount == 0 || thinCount == scene.lines.size()) {
      r.lineBuffer = makeBuffer(gl_, GL_TEXTURE_BUFFER, scene.lines);
    } else {
      std::vector<LineSegment> ordered(scene.lines);
      std::stable_partition(ordered.begin(), ordered.end(), thin);
      r.lineBuffer = makeBuffer(gl_, GL_TEXTURE_BUFFER, ordered);
    }
    gl_.GenTextures(1, &r.lineTexture);
    gl_.BindTexture(GL_TEXTURE_BUFFER, r.lineTexture);
    gl_.TexBuffer(GL_TEXTURE_BUFFER, GL_R32F, r.lineBuffer);
    gl_.GenVertexArrays(1, &r.lineArray);  // core profile draws need one, even without attributes
    r.thinLineCount = static_cast<GLsizei>(thinCount);
    r.wideLineCount = static_cast<GLsizei>(scene.lines.size() - thinCount);
    lines_ = scene.lines.size();
  }
  for (const auto& organ : r.organs) organ->upload(OrganUpload{scene, view, r.textures, palette});
  gl_.BindVertexArray(0);
  checkErrors(gl_, "upload");
}

void GlRenderer::useSurfaceProgram(const Program& program, const Camera& camera) {
  const Resources& r = *resources_;
  GLuint id = program.id;
  gl_.UseProgram(id);
  gl_.UniformMatrix4fv(program.uniform(gl_, "uViewProjection"), 1, GL_FALSE,
                       glm::value_ptr(camera.viewProjection()));
  gl_.Uniform1i(program.uniform(gl_, "uMaterials"), kMaterialUnit);
  gl_.Uniform1i(program.uniform(gl_, "uMaterialCount"), r.materialCount);
  gl_.Uniform1i(program.uniform(gl_, "uTexture"), 0);
  gl_.Uniform1i(program.twoSided, 1);
  gl_.Uniform3fv(program.uniform(gl_, "uForward"), 1, glm::value_ptr(camera.forward));
  gl_.Uniform3fv(program.uniform(gl_, "uRight"), 1, glm::value_ptr(camera.right));
  gl_.Uniform3fv(program.uniform(gl_, "uUp"), 1, glm::value_ptr(camera.up));
  gl_.Uniform1i(program.uniform(gl_, "uColorMap"), r.lighting.colorMap ? 1 : 0);
  gl_.Uniform3fv(program.uniform(gl_, "uColorMapLight"), 1,
                 glm::value_ptr(r.lighting.colorMapLight));
  gl_.Uniform1f(program.uniform(gl_, "uDiffuseReflection"), r.lighting.diffuseReflection);

  std::vector<glm::vec4> position, spot, attenuation;
  std::vector<glm::vec3> ambient, diffuse, specular;
  for (const LightSource& l : r.lighting.lights) {
    // OpenGL's default light 0 shines along the eye's line of sight, wherever the eye is.
    glm::vec3 vector = r.lighting.headlight ? -camera.forward : l.vector;
    position.emplace_back(vector, l.directional ? 0.0f : 1.0f);
    ambient.push_back(l.ambient);
    diffuse.push_back(l.diffuse);
    specular.push_back(l.specular);
    bool isSpot = l.spot && l.spotCutoff < 180;
    spot.emplace_back(l.spotDirection, isSpot ? std::cos(glm::radians(l.spotCutoff)) : -2.0f);
    attenuation.emplace_back(l.constantAttenuation, l.linearAttenuation, l.quadraticAttenuation,
                             l.spotExponent);
  }
  auto count = static_cast<GLsizei>(r.lighting.lights.size());
  gl_.Uniform1i(program.uniform(gl_, "uLightCount"), count);
  if (count == 0) return;
  gl_.Uniform4fv(program.uniform(gl_, "uLightPosition"), count, &position[0].x);
  gl_.Uniform3fv(program.uniform(gl_, "uLightAmbient"), count, &ambient[0].x);
  gl_.Uniform3fv(program.uniform(gl_, "uLightDiffuse"), count, &diffuse[0].x);
  gl_.Uniform3fv(program.uniform(gl_, "uLightSpecular"), count, &specular[0].x);
  gl_.Uniform4fv(program.uniform(gl_, "uLightSpot"), count, &spot[0].x);
  gl_.Uniform4fv(program.uniform(gl_, "uLightAttenuation"), count, &attenuation[0].x);
}

void GlRenderer::useLineProgram(const Program& program, const Camera& camera) {
  const Resources& r = *resources_;
  gl_.UseProgram(program.id);
  gl_.UniformMatrix4fv(program.uniform(gl_, "uViewProjection"), 1, GL_FALSE,
                       glm::value_ptr(camera.viewProjection()));
  gl_.Uniform1i(program.uniform(gl_, "uMaterials"), kMaterialUnit);
  gl_.Uniform1i(program.uniform(gl_, "uMaterialCount"), r.materialCount);
  gl_.Uniform1i(program.uniform(gl_, "uLines"), kLineUnit);
  gl_.ActiveTexture(GL_TEXTURE0 + kLineUnit);
  gl_.BindTexture(GL_TEXTURE_BUFFER, r.lineTexture);
  gl_.BindVertexArray(r.lineArray);
}

void GlRenderer::drawMesh(const Program& program, const Mesh& mesh) {
  const Resources& r = *resources_;
  gl_.Uniform1i(program.material, mesh.material);
  gl_.Uniform1i(program.twoSided, mesh.twoSided ? 1 : 0);
  if (mesh.texture >= 0) {
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_2D, r.textures[static_cast<std::size_t>(mesh.texture)]);
  }
  gl_.BindVertexArray(mesh.vertexArray);
  gl_.DrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
}

void GlRenderer::drawMeshes(const Camera& camera, std::vector<Mesh>::const_iterator begin,
                            std::vector<Mesh>::const_iterator end) {
  int shading = shadingOf(resources_->renderMode);
  const Program* current = nullptr;
  for (auto mesh = begin; mesh != end; ++mesh) {
    // A mesh without normals is shaded with its polygons' own.
    int meshShading = shading == 2 && !mesh->normals ? 1 : shading;
    const Program& p =
        surfaceProgram(static_cast<int>(Geometry::Mesh), meshShading, mesh->texture >= 0);
    if (&p != current) {
      useSurfaceProgram(p, camera);
      current = &p;
    }
    drawMesh(p, *mesh);
  }
}

void GlRenderer::draw(const Camera& camera) {
  const Resources& r = *resources_;
  gl_.Viewport(0, 0, camera.viewport.x, camera.viewport.y);
  gl_.ClearColor(r.background.r, r.background.g, r.background.b, 1.0f);
  gl_.ClearDepth(1.0);
  gl_.DepthMask(GL_TRUE);
  gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  // cpfg's `z buffer: off`: the last object drawn is the one seen.
  if (r.zBuffer) {
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LEQUAL);
  } else {
    gl_.Disable(GL_DEPTH_TEST);
  }
  gl_.Disable(GL_BLEND);
  gl_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl_.Disable(GL_CULL_FACE);
  gl_.Enable(GL_MULTISAMPLE);
  gl_.ActiveTexture(GL_TEXTURE0 + kMaterialUnit);
  gl_.BindTexture(GL_TEXTURE_BUFFER, r.materialTexture);

  // cpfg-manual §8.1.4: `wireframe` draws everything as wires, `fast` only spheres and discs.
  bool wires = wireframe_ || r.renderMode == RenderMode::Wireframe;
  GLenum meshMode = wires ? GL_LINE : GL_FILL;
  GLenum primitiveMode = wires || r.renderMode == RenderMode::Fast ? GL_LINE : GL_FILL;

  auto opaqueEnd =
      std::find_if(r.meshes.begin(), r.meshes.end(), [](const Mesh& m) { return m.transparent; });
  gl_.PolygonMode(GL_FRONT_AND_BACK, meshMode);
  drawMeshes(camera, r.meshes.begin(), opaqueEnd);

  // Spheres, discs and lines may each have a transparent colour.
  if (r.anyTransparent) gl_.Enable(GL_BLEND);
  gl_.PolygonMode(GL_FRONT_AND_BACK, primitiveMode);
  int shading = shadingOf(r.renderMode);
  if (r.sphereCount > 0) {
    const Program& p = surfaceProgram(static_cast<int>(Geometry::Sphere), shading, false);
    useSurfaceProgram(p, camera);
    gl_.Uniform1i(p.twoSided, 0);
    gl_.BindVertexArray(r.unitSphere.vertexArray);
    gl_.DrawElementsInstanced(GL_TRIANGLES, r.unitSphere.indexCount, GL_UNSIGNED_INT, nullptr,
                              r.sphereCount);
  }
  if (r.discCount > 0) {
    useSurfaceProgram(surfaceProgram(static_cast<int>(Geometry::Disc), shading, false), camera);
    gl_.BindVertexArray(r.unitDisc.vertexArray);
    gl_.DrawElementsInstanced(GL_TRIANGLES, r.unitDisc.indexCount, GL_UNSIGNED_INT, nullptr,
                              r.discCount);
  }

  gl_.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  if (r.thinLineCount > 0) {
    const Program& p = r.thinLineProgram;
    useLineProgram(p, camera);
    gl_.DrawArrays(GL_LINES, 0, 2 * r.thinLineCount);
  }
  if (r.wideLineCount > 0) {
    const Program& p = r.wideLineProgram;
    useLineProgram(p, camera);
    gl_.Uniform1i(p.uniform(gl_, "uPixelWidth"), r.lineStyle == LineStyle::Pixel ? 1 : 0);
    gl_.Uniform2f(p.uniform(gl_, "uViewport"), static_cast<float>(camera.viewport.x),
                  static_cast<float>(camera.viewport.y));
    bool perspective = camera.projection == Projection::Perspective;
    gl_.Uniform1i(p.uniform(gl_, "uPerspective"), perspective ? 1 : 0);
    // Parallel projection keeps w = 1, so no end is ever behind the eye.
    gl_.Uniform1f(p.uniform(gl_, "uNear"), perspective ? camera.nearPlane : 0.0f);
    gl_.Uniform3fv(p.uniform(gl_, "uEye"), 1, glm::value_ptr(camera.eye));
    gl_.Uniform3fv(p.uniform(gl_, "uForward"), 1, glm::value_ptr(camera.forward));
    gl_.Uniform3fv(p.uniform(gl_, "uRight"), 1, glm::value_ptr(camera.right));
    // The quads follow the thin segments in the buffer: gl_VertexID / 6 counts on from them.
    gl_.DrawArrays(GL_TRIANGLES, 6 * r.thinLineCount, 6 * r.wideLineCount);
  }
  // The organs take the light the surfaces have: the eye's, the first light's, or the colour
  // map's light direction.
  const glm::vec3 light = organLight(r.lighting, -camera.forward);
  for (std::size_t k = 0; k < r.organs.size(); ++k) {
    if (!hidden_[k]) r.organs[k]->draw(camera, light, detail_);
  }

  if (opaqueEnd != r.meshes.end()) {
    gl_.PolygonMode(GL_FRONT_AND_BACK, meshMode);
    gl_.Enable(GL_BLEND);
    gl_.DepthMask(GL_FALSE);
    drawMeshes(camera, opaqueEnd, r.meshes.end());
    gl_.DepthMask(GL_TRUE);
    gl_.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  r.labels->draw(camera);
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
  checkErrors(gl_, "draw");
}

}  // namespace hirsute
