#include "hirsute/hairs/feathers/feather_drawing.h"

#include <functional>
#include <glm/gtc/type_ptr.hpp>

#include "hirsute/interpreter/feather_part.h"
#include "hirsute/viewer/gl/gl_objects.h"

namespace hirsute {
namespace {

using gl::floatAttribute;
using gl::linkProgram;
using gl::makeBuffer;

constexpr char kVersion[] = "#version 330 core\n";

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
  nearSides_.clear();
}

void FeatherDrawing::take(const Scene& scene, const std::vector<GLuint>& textures) {
  release();
  scene_ = Scene{};
  scene_.organ<FeatherPart>().types = scene.organ<FeatherPart>().types;
  scene_.organ<FeatherPart>().feathers = scene.organ<FeatherPart>().feathers;
  scene_.organ<FeatherPart>().poses = scene.organ<FeatherPart>().poses;
  scene_.organ<FeatherPart>().maxVertices = scene.organ<FeatherPart>().maxVertices;
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
  buffers_ = FeatherBuffers{};
}

void FeatherDrawing::build(const std::vector<std::uint8_t>& levels) {
  release();
  buffers_ = buildFeatherBuffers(scene_, levels);
  const FeatherBuffers& b = buffers_;
  gl_.GenVertexArrays(1, &shaftArray_);
  gl_.BindVertexArray(shaftArray_);
  if (!b.shaftPositions.empty()) {
    vertexBuffers_[0] = makeBuffer(gl_, GL_ARRAY_BUFFER, b.shaftPositions);
    floatAttribute(gl_, 0, 3, 0, 0, false);
    vertexBuffers_[1] = makeBuffer(gl_, GL_ARRAY_BUFFER, b.shaftNormals);
    floatAttribute(gl_, 1, 3, 0, 0, false);
    vertexBuffers_[2] = makeBuffer(gl_, GL_ARRAY_BUFFER, b.shaftColors);
    floatAttribute(gl_, 2, 3, 0, 0, false);
    vertexBuffers_[3] = makeBuffer(gl_, GL_ELEMENT_ARRAY_BUFFER, b.shaftIndices);
  }
  gl_.GenVertexArrays(1, &barbArray_);
  gl_.BindVertexArray(barbArray_);
  if (!b.barbPositions.empty()) {
    vertexBuffers_[4] = makeBuffer(gl_, GL_ARRAY_BUFFER, b.barbPositions);
    floatAttribute(gl_, 0, 3, 0, 0, false);
    vertexBuffers_[5] = makeBuffer(gl_, GL_ARRAY_BUFFER, b.barbColors);
    floatAttribute(gl_, 1, 4, 0, 0, false);
    vertexBuffers_[6] = makeBuffer(gl_, GL_ARRAY_BUFFER, b.barbTexcoords);
    floatAttribute(gl_, 2, 2, 0, 0, false);
    gl_.GenBuffers(1, &barbIndices_);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, barbIndices_);
  }
  gl_.BindVertexArray(0);
  built_ = true;
}

void FeatherDrawing::draw(const Camera& camera, const glm::vec3& light, float /*detail*/) {
  if (scene_.organ<FeatherPart>().feathers.empty()) return;
  const std::vector<std::uint8_t> levels = featherDetailLevels(scene_, camera);
  if (!built_ || levels != buffers_.levels) {
    // Geometry past the limit at these levels is not built again each frame.
    if (!failure_.empty() && levels == failedLevels_) throw GeometryLimitError(failure_);
    try {
      build(levels);
    } catch (const GeometryLimitError& e) {
      release();
      buffers_ = FeatherBuffers{};
      failedLevels_ = levels;
      failure_ = e.what();
      throw;
    }
    failure_.clear();
  }

  // The vane order for this camera: the barb indices are rebuilt only when it changes.
  std::vector<char> nearSides(buffers_.parts.size());
  for (std::size_t i = 0; i < buffers_.parts.size(); ++i) {
    const FeatherBuffers::Part& part = buffers_.parts[i];
    const glm::vec3 towardsEye =
        camera.projection == Projection::Perspective ? camera.eye - part.position : -camera.forward;
    nearSides[i] = glm::dot(part.left, towardsEye) > 0 ? 1 : 0;
  }
  if (nearSides != nearSides_ && barbIndices_ != 0) {
    orderFeatherBarbs(buffers_, camera, order_, runs_);
    gl_.BindVertexArray(barbArray_);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, barbIndices_);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                   static_cast<GLsizeiptr>(order_.size() * sizeof(std::uint32_t)), order_.data(),
                   GL_STATIC_DRAW);
    nearSides_ = std::move(nearSides);
  }

  const glm::mat4 viewProjection = camera.viewProjection();
  if (!buffers_.shaftIndices.empty()) {
    gl_.UseProgram(shaftProgram_);
    gl_.UniformMatrix4fv(shaftViewProjection_, 1, GL_FALSE, glm::value_ptr(viewProjection));
    const glm::vec3 l = glm::length(light) > 0 ? glm::normalize(light) : -camera.forward;
    gl_.Uniform3fv(shaftLight_, 1, glm::value_ptr(l));
    gl_.BindVertexArray(shaftArray_);
    gl_.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(buffers_.shaftIndices.size()),
                     GL_UNSIGNED_INT, nullptr);
  }
  if (runs_.empty()) return;
  // Sec. 4.3.1: the barbs blend in their order; they test depth against the opaque scene but do
  // not write it, so that a barb behind another in the same feather still shows through.
  gl_.Enable(GL_BLEND);
  gl_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl_.DepthMask(GL_FALSE);
  gl_.UseProgram(barbProgram_);
  gl_.UniformMatrix4fv(barbViewProjection_, 1, GL_FALSE, glm::value_ptr(viewProjection));
  gl_.Uniform1i(barbTexture_, 0);
  gl_.BindVertexArray(barbArray_);
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
  gl_.DepthMask(GL_TRUE);
  gl_.Disable(GL_BLEND);
}

std::size_t FeatherDrawing::primitives() const {
  std::size_t n = buffers_.shaftIndices.size() / 3;
  for (const FeatherBuffers::Part& part : buffers_.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      if (vane.primitiveSize > 0) n += vane.count / static_cast<std::size_t>(vane.primitiveSize);
    }
  }
  return n;
}

const OrganDrawingType& featherDrawing() {
  static const OrganDrawingTypeOf<FeatherDrawing> type("feathers");
  return type;
}

}  // namespace hirsute
