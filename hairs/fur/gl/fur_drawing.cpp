#include "hirsute/hairs/fur/fur_drawing.h"

#include <glm/gtc/type_ptr.hpp>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_settings.h"
#include "hirsute/hairs/fur/fur_strand.h"
#include "hirsute/viewer/gl/gl_objects.h"

namespace hirsute {
namespace {

using gl::floatAttribute;
using gl::linkProgram;
using gl::makeBuffer;

constexpr char kVersion[] = "#version 330 core\n";

// Eq. 1 per vertex: the strand's Bézier (p_root, p_0, p) at h plus the curl of Eq. 4, which the
// wetness at the vertex unwinds; the strand's tangent goes on to the shading.
constexpr char kShellVertex[] = R"(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aTangent;
layout(location = 3) in vec2 aUv;
layout(location = 4) in vec2 aTexcoord;
layout(location = 5) in vec3 aTip;
uniform mat4 uViewProjection;
uniform int uLayers;
uniform float uLength, uCurlRadius, uCurlFrequency;
uniform sampler2D uWetness;
out vec2 vUv;
out vec2 vTexcoord;
out vec3 vTangent;
out vec3 vWorld;
flat out float vH;
void main() {
  float h = float(gl_InstanceID + 1) / float(uLayers);
  vec3 n = normalize(aNormal);
  vec3 u = normalize(aTangent);
  vec3 v = cross(n, u);
  vec3 rest = aPosition + uLength * n;
  float a = 1.0 - h;
  vec3 bend = a * a * aPosition + 2.0 * a * h * rest + h * h * aTip;
  vec3 bendTangent = 2.0 * a * (rest - aPosition) + 2.0 * h * (aTip - rest);
  float rho = textureLod(uWetness, aUv, 0.0).a;
  float k = (1.0 - rho) * uCurlRadius * uLength;
  float angle = uCurlFrequency * h;
  float c = cos(angle), s = sin(angle);
  vec3 curl = k * h * (c * u + s * v);
  vec3 curlTangent = k * ((c - uCurlFrequency * h * s) * u + (s + uCurlFrequency * h * c) * v);
  vTangent = bendTangent + curlTangent;
  vUv = aUv;
  vTexcoord = aTexcoord;
  vH = h;
  vWorld = bend + curl;
  gl_Position = uViewProjection * vec4(vWorld, 1.0);
}
)";

// Algorithm 2 (clumping by Eq. 5), the strand texels that reach h, and Eq. 6.
constexpr char kShellFragment[] = R"(
in vec2 vUv;
in vec2 vTexcoord;
in vec3 vTangent;
in vec3 vWorld;
flat in float vH;
uniform sampler2D uFur;
uniform sampler2D uWetness;
uniform sampler2D uColorTexture;
uniform bool uTextured;
uniform vec3 uColor;
uniform vec2 uTexcoordsPerUv;
uniform bool uWrapU;
uniform int uLayers;
uniform float uClumpShape, uSpecular, uPhong, uShadow, uClumpTexels;
uniform vec3 uLight;
uniform vec3 uEye;
uniform vec3 uForward;
uniform bool uPerspective;
out vec4 fragColor;
float profile(float h) {
  float bent = h;
  if (uLayers > 1) bent = h <= 1.0 / float(uLayers) ? 0.0 : 1.0 + log(h) / log(float(uLayers));
  return (1.0 - uClumpShape) * h + uClumpShape * bent;
}
void main() {
  vec2 uvColor = vUv;
  vec2 uvGeo = vTexcoord;
  vec4 mask = textureLod(uWetness, vUv, 0.0);
  if (mask.a > 0.0) {
    vec2 fromCentre = vUv - mask.xy;
    if (uWrapU) fromCentre.x -= floor(fromCentre.x + 0.5);
    if (length(fromCentre) > mask.z) discard;  // a pixel of another clump
    vec2 d = profile(vH) * mask.a * mask.z * uClumpTexels * fromCentre;
    if (textureLod(uWetness, vUv + d, 0.0).a == 0.0) discard;  // from a dry area
    uvColor += d;
    uvGeo += d * uTexcoordsPerUv;
  }
  float reach = texture(uFur, uvGeo).r;
  if (reach < vH) discard;  // no strand this high
  vec3 color = uTextured ? texture(uColorTexture, uvColor).rgb : uColor;
  vec3 T = normalize(vTangent);
  vec3 L = normalize(uLight);
  vec3 E = uPerspective ? normalize(uEye - vWorld) : -uForward;
  float tl = dot(T, L), te = dot(T, E);
  float sl = sqrt(max(0.0, 1.0 - tl * tl)), se = sqrt(max(0.0, 1.0 - te * te));
  vec3 diffuse = color * sl;
  float specular = uSpecular * pow(max(0.0, tl * te + sl * se), uPhong);
  float gamma = (uShadow - 1.0 + vH) / uShadow;
  fragColor = vec4(gamma * (diffuse + vec3(specular)), 1.0);
}
)";

// The mask's texels as one RGBA32F texture, row v, column u.
void uploadWetness(const GlFunctions& gl, GLuint texture, const FurSurface& surface) {
  gl.BindTexture(GL_TEXTURE_2D, texture);
  static const glm::vec4 kDry(0.0f);
  // A dry surface has no texels: one dry texel stands for them all.
  const bool wet = surface.wetnessSize > 0 && !surface.wetness.empty();
  const int size = wet ? surface.wetnessSize : 1;
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, size, size, 0, GL_RGBA, GL_FLOAT,
                wet ? static_cast<const void*>(surface.wetness.data()) : glm::value_ptr(kDry));
}

}  // namespace

struct FurDrawing::Surface {
  GLuint vertexArray = 0;
  GLuint buffers[7] = {};  // positions, normals, tangents, uv, texcoords, tips, indices
  GLuint wetness = 0;
  GLsizei indexCount = 0;
  int furTexture = 0;
  GLuint colorTexture = 0;  // 0: uColor
  glm::vec3 color{0.8f};
  FurAttributes attributes;
  glm::vec2 texcoordsPerUv{1.0f};
  bool wrapsU = false;
};

FurDrawing::FurDrawing(const GlFunctions& gl) : gl_(gl) {
  program_ = linkProgram(gl_, {kVersion, kShellVertex}, {kVersion, kShellFragment});
}

FurDrawing::~FurDrawing() {
  release();
  gl_.DeleteProgram(program_);
}

void FurDrawing::release() {
  for (Surface& s : surfaces_) {
    gl_.DeleteVertexArrays(1, &s.vertexArray);
    gl_.DeleteBuffers(7, s.buffers);
    gl_.DeleteTextures(1, &s.wetness);
  }
  surfaces_.clear();
  if (!furTextures_.empty())
    gl_.DeleteTextures(static_cast<GLsizei>(furTextures_.size()), furTextures_.data());
  furTextures_.clear();
}

void FurDrawing::upload(const OrganUpload& upload) {
  const Scene& scene = upload.scene;
  const ViewSettings& view = upload.view;
  const std::vector<GLuint>& textures = upload.textures;
  const std::vector<Material>& palette = upload.palette;
  release();
  layers_ = view.organ<FurSettings>().layers;
  for (const FurTexture& fur : scene.organ<FurPart>().textures) {
    GLuint texture = 0;
    gl_.GenTextures(1, &texture);
    gl_.BindTexture(GL_TEXTURE_2D, texture);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, fur.size, fur.size, 0, GL_RED, GL_UNSIGNED_BYTE,
                   fur.lengths.data());
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    furTextures_.push_back(texture);
  }
  for (const FurSurface& fur : scene.organ<FurPart>().surfaces) {
    if (fur.attributes < 0 || fur.indices.empty()) continue;
    Surface s;
    s.attributes = scene.organ<FurPart>().attributes[static_cast<std::size_t>(fur.attributes)];
    s.furTexture = fur.furTexture;
    s.texcoordsPerUv = fur.texcoordsPerUv;
    s.wrapsU = fur.wrapsU;
    const std::size_t material = static_cast<std::size_t>(fur.material);
    s.color = material < palette.size() ? palette[material].diffuse : glm::vec3(0.8f);
    const int colourTexture = s.attributes.sceneTexture();
    if (colourTexture >= 0 && static_cast<std::size_t>(colourTexture) < textures.size())
      s.colorTexture = textures[static_cast<std::size_t>(colourTexture)];
    gl_.GenVertexArrays(1, &s.vertexArray);
    gl_.BindVertexArray(s.vertexArray);
    s.buffers[0] = makeBuffer(gl_, GL_ARRAY_BUFFER, fur.positions);
    floatAttribute(gl_, 0, 3, 0, 0, false);
    s.buffers[1] = makeBuffer(gl_, GL_ARRAY_BUFFER, fur.normals);
    floatAttribute(gl_, 1, 3, 0, 0, false);
    s.buffers[2] = makeBuffer(gl_, GL_ARRAY_BUFFER, fur.tangents);
    floatAttribute(gl_, 2, 3, 0, 0, false);
    s.buffers[3] = makeBuffer(gl_, GL_ARRAY_BUFFER, fur.uv);
    floatAttribute(gl_, 3, 2, 0, 0, false);
    s.buffers[4] = makeBuffer(gl_, GL_ARRAY_BUFFER, fur.texcoords);
    floatAttribute(gl_, 4, 2, 0, 0, false);
    s.buffers[5] = makeBuffer(gl_, GL_ARRAY_BUFFER, fur.tips);
    floatAttribute(gl_, 5, 3, 0, 0, false);
    s.buffers[6] = makeBuffer(gl_, GL_ELEMENT_ARRAY_BUFFER, fur.indices);
    s.indexCount = static_cast<GLsizei>(fur.indices.size());
    gl_.GenTextures(1, &s.wetness);
    uploadWetness(gl_, s.wetness, fur);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, fur.wrapsU ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    surfaces_.push_back(s);
  }
  gl_.BindVertexArray(0);
}

void FurDrawing::update(const Scene& scene, const std::vector<GLuint>& /*textures*/) {
  std::size_t next = 0;
  for (const FurSurface& fur : scene.organ<FurPart>().surfaces) {
    if (fur.attributes < 0 || fur.indices.empty()) continue;
    if (next >= surfaces_.size()) break;
    Surface& s = surfaces_[next++];
    gl_.BindBuffer(GL_ARRAY_BUFFER, s.buffers[5]);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(fur.tips.size() * sizeof(glm::vec3)),
                   fur.tips.data(), GL_DYNAMIC_DRAW);
    uploadWetness(gl_, s.wetness, fur);
  }
}

std::size_t FurDrawing::instances() const {
  return surfaces_.size();
}

std::size_t FurDrawing::shellTriangles() const {
  std::size_t n = 0;
  for (const Surface& s : surfaces_) n += static_cast<std::size_t>(s.indexCount / 3);
  return n * static_cast<std::size_t>(layers_);
}

void FurDrawing::draw(const Camera& camera, const glm::vec3& light, float /*detail*/) {
  if (surfaces_.empty()) return;
  gl_.UseProgram(program_);
  auto uniform = [this](const char* name) { return gl_.GetUniformLocation(program_, name); };
  gl_.UniformMatrix4fv(uniform("uViewProjection"), 1, GL_FALSE,
                       glm::value_ptr(camera.viewProjection()));
  gl_.Uniform1i(uniform("uLayers"), layers_);
  gl_.Uniform3fv(uniform("uLight"), 1, glm::value_ptr(light));
  gl_.Uniform3fv(uniform("uEye"), 1, glm::value_ptr(camera.eye));
  gl_.Uniform3fv(uniform("uForward"), 1, glm::value_ptr(camera.forward));
  gl_.Uniform1i(uniform("uPerspective"), camera.projection == Projection::Perspective ? 1 : 0);
  gl_.Uniform1f(uniform("uClumpTexels"), fur::kClumpTexels);
  gl_.Uniform1i(uniform("uFur"), 0);
  gl_.Uniform1i(uniform("uWetness"), 1);
  gl_.Uniform1i(uniform("uColorTexture"), 2);
  for (const Surface& s : surfaces_) {
    const FurAttributes& a = s.attributes;
    gl_.Uniform1f(uniform("uLength"), a.length);
    gl_.Uniform1f(uniform("uCurlRadius"), a.curlRadius);
    gl_.Uniform1f(uniform("uCurlFrequency"), a.curlFrequency);
    gl_.Uniform1f(uniform("uClumpShape"), a.clumpShape);
    gl_.Uniform1f(uniform("uSpecular"), a.specular);
    gl_.Uniform1f(uniform("uPhong"), a.phong);
    gl_.Uniform1f(uniform("uShadow"), a.shadow);
    gl_.Uniform3fv(uniform("uColor"), 1, glm::value_ptr(s.color));
    gl_.Uniform2f(uniform("uTexcoordsPerUv"), s.texcoordsPerUv.x, s.texcoordsPerUv.y);
    gl_.Uniform1i(uniform("uWrapU"), s.wrapsU ? 1 : 0);
    gl_.Uniform1i(uniform("uTextured"), s.colorTexture != 0 ? 1 : 0);
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_2D, furTextures_[static_cast<std::size_t>(s.furTexture)]);
    gl_.ActiveTexture(GL_TEXTURE1);
    gl_.BindTexture(GL_TEXTURE_2D, s.wetness);
    gl_.ActiveTexture(GL_TEXTURE2);
    gl_.BindTexture(GL_TEXTURE_2D, s.colorTexture);
    gl_.BindVertexArray(s.vertexArray);
    gl_.DrawElementsInstanced(GL_TRIANGLES, s.indexCount, GL_UNSIGNED_INT, nullptr, layers_);
  }
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindVertexArray(0);
}

const OrganDrawingType& furDrawing() {
  static const OrganDrawingTypeOf<FurDrawing> type("fur");
  return type;
}

}  // namespace hirsute
