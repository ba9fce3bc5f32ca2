#include "hirsute/hairs/feathers/feather_drawing.h"

#include <functional>
#include <glm/gtc/type_ptr.hpp>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/viewer/gl/gl_objects.h"

namespace hirsute {
namespace {

using gl::floatAttribute;
using gl::linkProgram;
using gl::makeBuffer;

constexpr char kVersion[] = "#version 330 core\n";
// Vertices streamed a draw (FeatherDrawing), 9 MB of barb vertices at the most: the coat of
// 10 000 feathers renders faster and in half the memory than with four times as many
// (docs/feathers.md, "Dense coats").
constexpr std::size_t kStreamVertices = std::size_t{1} << 18;

// The shafts: lit on both sides by one light, a fifth of it ambient.
constexpr char kShaftVertex[] = R"(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aColor;
uniform mat4 uViewProjection;
uniform vec3 uLight;
out vec3 vColor;
void main() {
  float lit = abs(dot(normalize(aNormal), uLight));
  vColor = aColor * (0.2 + 0.8 * lit);
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";
constexpr char kShaftFragment[] = R"(
in vec3 vColor;
out vec4 fragColor;
void main() { fragColor = vec4(vColor, 1.0); }
)";

// The barbs: their colour and alpha (fading to the tip and, on strips, to the edges), times the
// texture in the type's mapping (Sec. 4.3.3).
constexpr char kBarbVertex[] = R"(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aColor;
layout(location = 2) in vec2 aTexcoord;
uniform mat4 uViewProjection;
out vec4 vColor;
out vec2 vTexcoord;
void main() {
  vColor = aColor;
  vTexcoord = aTexcoord;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";
constexpr char kBarbFragment[] = R"(
in vec4 vColor;
in vec2 vTexcoord;
uniform bool uTextured;
uniform sampler2D uTexture;
out vec4 fragColor;
void main() {
  vec4 c = vColor;
  if (uTextured) c.rgb *= texture(uTexture, vTexcoord).rgb;
  fragColor = c;
}
)";

}  // namespace

FeatherDrawing::FeatherDrawing(const GlFunctions& gl) : gl_(gl) {
  shaftProgram_ = linkProgram(gl_, {kVersion, kShaftVertex}, {kVersion, kShaftFragment});
  try {
    barbProgram_ = linkProgram(gl_, {kVersion, kBarbVertex}, {kVersion, kBarbFragment});
  } catch (...) {
    gl_.DeleteProgram(shaftProgram_);
    throw;
  }
  shaftViewProjection_ = gl_.GetUniformLocation(shaftProgram_, "uViewProjection");
  shaftLight_ = gl_.GetUniformLocation(shaftProgram_, "uLight");
  barbViewProjection_ = gl_.GetUniformLocation(barbProgram_, "uViewProjection");
  barbTextured_ = gl_.GetUniformLocation(barbProgram_, "uTextured");
  barbTexture_ = gl_.GetUniformLocation(barbProgram_, "uTexture");
}

FeatherDrawing::~FeatherDrawing() {
  release();
  gl_.DeleteProgram(shaftProgram_);
  gl_.DeleteProgram(barbProgram_);
}

void FeatherDrawing::release() {
  for (GLuint* array : {&shaftArray_, &barbArray_}) {
    if (*array) gl_.DeleteVertexArrays(1, array);
    *array = 0;
  }
  for (GLuint& buffer : vertexBuffers_) {
    if (buffer) gl_.DeleteBuffers(1, &buffer);
    buffer = 0;
  }
  if (barbIndices_) gl_.DeleteBuffers(1, &barbIndices_);
  barbIndices_ = 0;
  built_ = false;
}

void FeatherDrawing::take(const Scene& scene, const std::vector<GLuint>& textures) {
  release();
  scene_ = Scene{};
  scene_.organ<FeatherPart>().types = scene.organ<FeatherPart>().types;
  scene_.organ<FeatherPart>().feathers = scene.organ<FeatherPart>().feathers;
  scene_.organ<FeatherPart>().poses = scene.organ<FeatherPart>().poses;
  scene_.organ<FeatherPart>().maxVertices = scene.organ<FeatherPart>().maxVertices;
  scene_.organ<FeatherPart>().fullDetail = scene.organ<FeatherPart>().fullDetail;
  scene_.materials = scene.materials;
  // The feathers' own images, where they stand in the Scene's list: a blended type's cross-fade
  // is drawn into its barbs' colours from them.
  scene_.textures.resize(scene.textures.size());
  std::function<void(const FeatherType&)> keepTextures = [&](const FeatherType& type) {
    const int t = type.appearance.sceneTexture;
    if (t >= 0 && static_cast<std::size_t>(t) < scene.textures.size())
      scene_.textures[static_cast<std::size_t>(t)] = scene.textures[static_cast<std::size_t>(t)];
    if (type.afterfeather) keepTextures(*type.afterfeather);
  };
  for (const FeatherType& type : scene.organ<FeatherPart>().types) keepTextures(type);
  textures_ = textures;
  instances_ = FeatherInstances{};
}

void FeatherDrawing::build(const std::vector<std::uint8_t>& levels) {
  release();
  instances_ = buildFeatherInstances(scene_, levels, scene_.organ<FeatherPart>().fullDetail);
  // The stream's buffers: their storage is given anew on every draw (streamShafts, streamBarbs).
  gl_.GenBuffers(7, vertexBuffers_);
  gl_.GenBuffers(1, &barbIndices_);
  gl_.GenVertexArrays(1, &shaftArray_);
  gl_.BindVertexArray(shaftArray_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffers_[0]);
  floatAttribute(gl_, 0, 3, 0, 0, false);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffers_[1]);
  floatAttribute(gl_, 1, 3, 0, 0, false);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffers_[2]);
  floatAttribute(gl_, 2, 3, 0, 0, false);
  gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, vertexBuffers_[3]);
  gl_.GenVertexArrays(1, &barbArray_);
  gl_.BindVertexArray(barbArray_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffers_[4]);
  floatAttribute(gl_, 0, 3, 0, 0, false);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffers_[5]);
  floatAttribute(gl_, 1, 4, 0, 0, false);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffers_[6]);
  floatAttribute(gl_, 2, 2, 0, 0, false);
  gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, barbIndices_);
  gl_.BindVertexArray(0);
  built_ = true;
}

namespace {

// New storage for `buffer` (bound to `target`) holding `data`.
template <typename T>
void streamTo(const GlFunctions& gl, GLenum target, GLuint buffer, const std::vector<T>& data) {
  gl.BindBuffer(target, buffer);
  gl.BufferData(target, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                GL_STREAM_DRAW);
}

}  // namespace

void FeatherDrawing::draw(const Camera& camera, const glm::vec3& light, float /*detail*/) {
  if (scene_.organ<FeatherPart>().feathers.empty()) return;
  const std::vector<std::uint8_t> levels = featherDetailLevels(scene_, camera);
  if (!built_ || levels != instances_.levels) {
    // Geometry past the limit at these levels is not built again each frame.
    if (!failure_.empty() && levels == failedLevels_) throw GeometryLimitError(failure_);
    try {
      build(levels);
    } catch (const GeometryLimitError& e) {
      release();
      instances_ = FeatherInstances{};
      failedLevels_ = levels;
      failure_ = e.what();
      throw;
    }
    failure_.clear();
  }
  const FeatherBuffers& b = instances_.geometry;
  const std::size_t feathers = instances_.templateOf.size();
  const glm::mat4 viewProjection = camera.viewProjection();
  FeatherBuffers& s = stream_;

  // The shafts, opaque: every feather's placed shaft, a draw for each full stream.
  if (!b.shaftIndices.empty()) {
    gl_.UseProgram(shaftProgram_);
    gl_.UniformMatrix4fv(shaftViewProjection_, 1, GL_FALSE, glm::value_ptr(viewProjection));
    const glm::vec3 l = glm::length(light) > 0 ? glm::normalize(light) : -camera.forward;
    gl_.Uniform3fv(shaftLight_, 1, glm::value_ptr(l));
    gl_.BindVertexArray(shaftArray_);
    auto flush = [&] {
      if (s.shaftIndices.empty()) return;
      streamTo(gl_, GL_ARRAY_BUFFER, vertexBuffers_[0], s.shaftPositions);
      streamTo(gl_, GL_ARRAY_BUFFER, vertexBuffers_[1], s.shaftNormals);
      streamTo(gl_, GL_ARRAY_BUFFER, vertexBuffers_[2], s.shaftColors);
      streamTo(gl_, GL_ELEMENT_ARRAY_BUFFER, vertexBuffers_[3], s.shaftIndices);
      gl_.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(s.shaftIndices.size()), GL_UNSIGNED_INT,
                       nullptr);
      s.shaftPositions.clear();
      s.shaftNormals.clear();
      s.shaftColors.clear();
      s.shaftIndices.clear();
    };
    for (std::size_t i = 0; i < feathers; ++i) {
      const FeatherInstances::Template& t = instances_.templates[instances_.templateOf[i]];
      if (t.shaftIndexCount == 0) continue;
      if (s.shaftPositions.size() + t.shaftVertexCount > kStreamVertices) {
        flush();
        gl_.Finish();  // llvmpipe keeps what a frame drew until it is rasterised
      }
      const glm::mat4& toWorld = instances_.toWorld[i];
      // A rotation and a uniform scale (featherToWorld): normals turn with the linear part.
      const glm::mat3 linear(toWorld);
      const auto base = static_cast<std::uint32_t>(s.shaftPositions.size());
      for (std::uint32_t v = t.firstShaftVertex; v < t.firstShaftVertex + t.shaftVertexCount; ++v) {
        s.shaftPositions.emplace_back(toWorld * glm::vec4(b.shaftPositions[v], 1.0f));
        s.shaftNormals.push_back(linear * b.shaftNormals[v]);
        s.shaftColors.push_back(b.shaftColors[v]);
      }
      for (std::uint32_t k = t.firstShaftIndex; k < t.firstShaftIndex + t.shaftIndexCount; ++k)
        s.shaftIndices.push_back(base + b.shaftIndices[k] - t.firstShaftVertex);
    }
    flush();
  }
  if (b.vaneIndices.empty()) return;

  // Sec. 4.3.1: the barbs blend in their order (the Scene's feathers in turn; in each, the vane
  // farther from the eye from the rachis out, then the nearer from the tip in); they test depth
  // against the opaque scene but do not write it, so that a barb behind another in the same
  // feather still shows through.
  gl_.Enable(GL_BLEND);
  gl_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl_.DepthMask(GL_FALSE);
  gl_.UseProgram(barbProgram_);
  gl_.UniformMatrix4fv(barbViewProjection_, 1, GL_FALSE, glm::value_ptr(viewProjection));
  gl_.Uniform1i(barbTexture_, 0);
  gl_.BindVertexArray(barbArray_);
  auto flush = [&] {
    if (s.vaneIndices.empty()) return;
    streamTo(gl_, GL_ARRAY_BUFFER, vertexBuffers_[4], s.barbPositions);
    streamTo(gl_, GL_ARRAY_BUFFER, vertexBuffers_[5], s.barbColors);
    streamTo(gl_, GL_ARRAY_BUFFER, vertexBuffers_[6], s.barbTexcoords);
    streamTo(gl_, GL_ELEMENT_ARRAY_BUFFER, barbIndices_, s.vaneIndices);
    for (const FeatherDrawRun& run : runs_) {
      const bool textured = run.texture >= 0 &&
                            static_cast<std::size_t>(run.texture) < textures_.size() &&
                            textures_[static_cast<std::size_t>(run.texture)] != 0;
      gl_.Uniform1i(barbTextured_, textured ? 1 : 0);
      if (textured) {
        gl_.ActiveTexture(GL_TEXTURE0);
        gl_.BindTexture(GL_TEXTURE_2D, textures_[static_cast<std::size_t>(run.texture)]);
      }
      gl_.DrawElements(run.triangles ? GL_TRIANGLES : GL_LINES, static_cast<GLsizei>(run.count),
                       GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(run.first * sizeof(std::uint32_t)));
    }
    s.barbPositions.clear();
    s.barbColors.clear();
    s.barbTexcoords.clear();
    s.vaneIndices.clear();
    runs_.clear();
  };
  // A vane's indices, from `first`, onto the feather's vertices placed from `base`.
  auto appendVane = [&](const FeatherBuffers::Vane& vane, std::uint32_t first, std::uint32_t base,
                        std::uint32_t templateFirst) {
    if (vane.count == 0) return;
    const bool triangles = vane.primitiveSize == 3;
    if (runs_.empty() || runs_.back().texture != vane.texture ||
        runs_.back().triangles != triangles) {
      runs_.push_back(FeatherDrawRun{vane.texture, triangles,
                                     static_cast<std::uint32_t>(s.vaneIndices.size()), 0});
    }
    for (std::uint32_t k = first; k < first + vane.count; ++k)
      s.vaneIndices.push_back(base + b.vaneIndices[k] - templateFirst);
    runs_.back().count += vane.count;
  };
  for (std::size_t i = 0; i < feathers; ++i) {
    const FeatherInstances::Template& t = instances_.templates[instances_.templateOf[i]];
    if (t.barbVertexCount == 0) continue;
    if (s.barbPositions.size() + t.barbVertexCount > kStreamVertices) {
      flush();
      gl_.Finish();  // llvmpipe keeps what a frame drew until it is rasterised
    }
    const glm::mat4& toWorld = instances_.toWorld[i];
    const auto base = static_cast<std::uint32_t>(s.barbPositions.size());
    for (std::uint32_t v = t.firstBarbVertex; v < t.firstBarbVertex + t.barbVertexCount; ++v) {
      s.barbPositions.emplace_back(toWorld * glm::vec4(b.barbPositions[v], 1.0f));
      s.barbColors.push_back(b.barbColors[v]);
      s.barbTexcoords.push_back(b.barbTexcoords[v]);
    }
    for (std::uint32_t p = t.firstPart; p < t.firstPart + t.partCount; ++p) {
      const FeatherBuffers::Part& part = b.parts[p];
      const glm::vec3 position = glm::vec3(toWorld * glm::vec4(part.position, 1.0f));
      const glm::vec3 left = glm::mat3(toWorld) * part.left;
      const glm::vec3 towardsEye =
          camera.projection == Projection::Perspective ? camera.eye - position : -camera.forward;
      const bool leftNearer = glm::dot(left, towardsEye) > 0;
      const FeatherBuffers::Vane& nearer = part.vanes[leftNearer ? 0 : 1];
      const FeatherBuffers::Vane& farther = part.vanes[leftNearer ? 1 : 0];
      appendVane(farther, farther.first, base, t.firstBarbVertex);
      appendVane(nearer, nearer.tipInwardFirst, base, t.firstBarbVertex);
    }
  }
  flush();
  gl_.DepthMask(GL_TRUE);
  gl_.Disable(GL_BLEND);
}

std::size_t FeatherDrawing::primitives() const {
  std::size_t n = 0;
  for (std::uint32_t t : instances_.templateOf) n += instances_.templates[t].primitives;
  return n;
}

const OrganDrawingType& featherDrawing() {
  static const OrganDrawingTypeOf<FeatherDrawing> type("feathers");
  return type;
}

}  // namespace hirsute
