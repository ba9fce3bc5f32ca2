// Plant hairs in the GL renderer: instanced template segments (docs/design.md, "Plant hairs").
#include "hirsute/hairs/plant/hair_drawing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>
#include <tuple>
#include <utility>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/viewer/gl/gl_objects.h"
#include "hirsute/viewer/gl/gl_shaders.h"

namespace hirsute {

using gl::floatAttribute;
using gl::linkProgram;
using gl::makeBuffer;

// The hairs of one template: its segments (GL_LINES pairs, in the hair's own frame) and a vertex
// array that reads them per vertex and the template's range of the shared instance buffer per
// instance.
struct HairDrawing::Batch {
  // Two vertex arrays over the same segments: the hairs in placement order (drawn in full:
  // consecutive hairs land in the same screen tiles) and in levels (prefixes for level of detail).
  GLuint vertexArray = 0, levelVertexArray = 0, segments = 0;
  GLsizei vertexCount = 0;    // two a segment
  // The template's filled triangles (HairTemplate::triangles), read the same way.
  GLuint triangleVertexArray = 0, triangleLevelVertexArray = 0, triangles = 0;
  GLsizei triangleVertexCount = 0;  // three a triangle
  GLsizei instanceCount = 0;  // its hairs, in hash order
  glm::vec4 color{1.0f};      // unlit, as the shaders' unlit(material)
};

namespace {

// A hair as the hair vertex shader reads it: 24 bytes of the Hair's 32.
struct HairInstance {
  glm::vec3 root;
  std::array<std::int16_t, 4> orientation;
  float length;
};
static_assert(sizeof(HairInstance) == 24, "the hair attributes read 24 bytes an instance");

// A 32-bit integer hash with good avalanche (Wellons' lowbias32): the order of a template's hairs
// on the GPU (upload). Hairs are placed segment by segment, so their index follows the surface;
// dealt by this hash, every prefix of them is spread over the whole plant.
std::uint32_t hairHash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// Plant hairs (Fuhrer et al. 2004, Sec. 3.2: template hairs instanced and drawn as antialiased
// lines): one draw per template, its segments as GL_LINES pairs in the hair's own frame
// (attribute 0), each instance a hair's root, orientation (a unit quaternion from normalized
// shorts) and length; template vertex p lands at root + length · (orientation · p), as
// Hair::place. The colour is the template material's, unlit, set once a draw.
constexpr char kHairVertexMain[] = R"(
layout(location = 0) in vec3 aTemplate;
layout(location = 3) in vec3 aRoot;
layout(location = 4) in vec4 aOrientation;  // (x, y, z, w)
layout(location = 5) in float aLength;
uniform mat4 uViewProjection;
uniform vec4 uColor;
flat out vec4 vColor;
void main() {
  vec4 q = normalize(aOrientation);
  // q · p · q* for a unit quaternion: p + 2w (v × p) + 2 v × (v × p), v = q.xyz.
  vec3 t = 2.0 * cross(q.xyz, aTemplate);
  vec3 rotated = aTemplate + q.w * t + cross(q.xyz, t);
  vColor = uColor;
  gl_Position = uViewProjection * vec4(aRoot + aLength * rotated, 1.0);
}
)";

constexpr int kHairLevelBits = 6;
constexpr std::size_t kHairLevels = std::size_t{1} << kHairLevelBits;

}  // namespace

HairDrawing::HairDrawing(const GlFunctions& gl) : gl_(gl) {
  program_ = linkProgram(gl_, {shaders::kVersion, kHairVertexMain},
                         {shaders::kVersion, shaders::kLineFragmentMain});
  viewProjection_ = gl_.GetUniformLocation(program_, "uViewProjection");
  color_ = gl_.GetUniformLocation(program_, "uColor");
}

HairDrawing::~HairDrawing() {
  release();
  gl_.DeleteProgram(program_);
}

void HairDrawing::release() {
  for (Batch& batch : batches_) {
    gl_.DeleteVertexArrays(1, &batch.vertexArray);
    gl_.DeleteVertexArrays(1, &batch.levelVertexArray);
    gl_.DeleteBuffers(1, &batch.segments);
    if (batch.triangles) {
      gl_.DeleteVertexArrays(1, &batch.triangleVertexArray);
      gl_.DeleteVertexArrays(1, &batch.triangleLevelVertexArray);
      gl_.DeleteBuffers(1, &batch.triangles);
    }
  }
  batches_.clear();
  for (GLuint* b : {&instances_, &instancesInOrder_}) {
    if (*b) gl_.DeleteBuffers(1, b);
    *b = 0;
  }
  hairs_ = segments_ = 0;
}

// Hairs are instances, not copies (docs/design.md, "Plant hairs"): each template's
// segments go up once, and the hairs, grouped by template with a counting sort, go up as 24-byte
// instances, once ordered within their template into levels by hairHash and once in placement
// order.
void HairDrawing::upload(const OrganUpload& upload) {
  const HairPart& part = upload.scene.organ<HairPart>();
  const std::vector<Material>& palette = upload.palette;
  release();
  const int materialCount = static_cast<int>(palette.size());
  const std::size_t templates = part.templates.size();
  std::vector<std::vector<glm::vec3>> ends(templates);
  for (std::size_t t = 0; t < templates; ++t) {
    for (const auto& polyline : part.templates[t].polylines) {
      for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        ends[t].push_back(polyline[i]);
        ends[t].push_back(polyline[i + 1]);
      }
    }
  }
  // One counting sort by template and, within a template, by level: hairHash's top bits deal
  // the hairs into kHairLevels random, equally likely levels, each spread over the whole plant,
  // and within a level the hairs keep their placement order. A prefix is whole levels (a uniform
  // subset) and at most part of one more (under 1/kHairLevels of the hairs, the one place where
  // a prefix is not uniform): level of detail draws such a prefix. Drawn in full, the hairs come
  // from a second copy in placement order, whose consecutive segments land in the same screen
  // tiles: on the oriental poppy llvmpipe draws the hairs in 1.2 times the time of raw GL_LINES
  // this way, in 1.35 times in levels, in 1.7 times fully hashed (hirsute_hair_render_bench
  // --hairs-only). The copy costs 24 bytes a hair of GL memory.
  const std::size_t buckets = templates * kHairLevels;
  auto bucketOf = [&](std::size_t i) {
    return part.hairs[i].templateIndex * kHairLevels +
           (hairHash(static_cast<std::uint32_t>(i)) >> (32 - kHairLevelBits));
  };
  auto drawn = [&](const Hair& hair) {
    return hair.templateIndex < templates &&
           (!ends[hair.templateIndex].empty() ||
            !part.templates[hair.templateIndex].triangles.empty());
  };
  std::vector<std::size_t> start(buckets + 1, 0);
  for (std::size_t i = 0; i < part.hairs.size(); ++i) {
    if (drawn(part.hairs[i])) ++start[bucketOf(i) + 1];
  }
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  const std::size_t count = start[buckets];
  if (count == 0) return;
  std::vector<HairInstance> instances(count), inOrder(count);
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    std::vector<std::size_t> nextInOrder(templates);
    for (std::size_t t = 0; t < templates; ++t) nextInOrder[t] = start[t * kHairLevels];
    for (std::size_t i = 0; i < part.hairs.size(); ++i) {
      const Hair& hair = part.hairs[i];
      if (!drawn(hair)) continue;
      const HairInstance instance{hair.root, hair.orientation, hair.length};
      instances[next[bucketOf(i)]++] = instance;
      inOrder[nextInOrder[hair.templateIndex]++] = instance;
    }
  }
  std::vector<std::size_t> first(templates + 1);
  for (std::size_t t = 0; t <= templates; ++t) first[t] = start[t * kHairLevels];
  instances_ = makeBuffer(gl_, GL_ARRAY_BUFFER, instances);
  instancesInOrder_ = makeBuffer(gl_, GL_ARRAY_BUFFER, inOrder);

  for (std::size_t t = 0; t < templates; ++t) {
    std::size_t hairs = first[t + 1] - first[t];
    if (hairs == 0) continue;
    Batch batch;
    int material = std::clamp(part.templates[t].material, 0, materialCount - 1);
    const Material& m = palette[static_cast<std::size_t>(material)];
    batch.color = glm::vec4(m.diffuse, 1.0f - m.transparency);
    batch.vertexCount = static_cast<GLsizei>(ends[t].size());
    batch.instanceCount = static_cast<GLsizei>(hairs);
    batch.segments = makeBuffer(gl_, GL_ARRAY_BUFFER, ends[t]);
    const std::vector<glm::vec3>& triangles = part.templates[t].triangles;
    batch.triangleVertexCount = static_cast<GLsizei>(triangles.size());
    if (!triangles.empty()) batch.triangles = makeBuffer(gl_, GL_ARRAY_BUFFER, triangles);
    // GL 3.3 has no base instance: each template's vertex arrays start at its own hairs.
    const std::size_t base = first[t] * sizeof(HairInstance);
    for (auto [vertexArray, shape, buffer] :
         {std::tuple{&batch.vertexArray, batch.segments, instancesInOrder_},
          std::tuple{&batch.levelVertexArray, batch.segments, instances_},
          std::tuple{&batch.triangleVertexArray, batch.triangles, instancesInOrder_},
          std::tuple{&batch.triangleLevelVertexArray, batch.triangles, instances_}}) {
      if (shape == 0) continue;
      gl_.GenVertexArrays(1, vertexArray);
      gl_.BindVertexArray(*vertexArray);
      gl_.BindBuffer(GL_ARRAY_BUFFER, shape);
      floatAttribute(gl_, 0, 3, 0, 0, false);
      gl_.BindBuffer(GL_ARRAY_BUFFER, buffer);
      constexpr auto stride = static_cast<GLsizei>(sizeof(HairInstance));
      floatAttribute(gl_, 3, 3, stride, base + offsetof(HairInstance, root), true);
      gl_.EnableVertexAttribArray(4);
      gl_.VertexAttribPointer(
          4, 4, GL_SHORT, GL_TRUE, stride,
          reinterpret_cast<const void*>(base + offsetof(HairInstance, orientation)));
      gl_.VertexAttribDivisor(4, 1);
      floatAttribute(gl_, 5, 1, stride, base + offsetof(HairInstance, length), true);
    }
    batches_.push_back(batch);
    hairs_ += hairs;
    segments_ += hairs * ends[t].size() / 2;
  }
}

void HairDrawing::draw(const Camera& camera, const glm::vec3& /*light*/, float fraction) {
  if (fraction <= 0 || batches_.empty()) return;
  gl_.UseProgram(program_);
  gl_.UniformMatrix4fv(viewProjection_, 1, GL_FALSE, glm::value_ptr(camera.viewProjection()));
  for (const Batch& batch : batches_) {
    // The prefix of the hash-ordered hairs: a uniform subset of the template's hairs.
    auto instances =
        static_cast<GLsizei>(std::lround(static_cast<double>(fraction) * batch.instanceCount));
    if (instances == 0) continue;
    gl_.Uniform4fv(color_, 1, glm::value_ptr(batch.color));
    const bool whole = instances == batch.instanceCount;
    if (batch.vertexCount > 0) {
      gl_.BindVertexArray(whole ? batch.vertexArray : batch.levelVertexArray);
      gl_.DrawArraysInstanced(GL_LINES, 0, batch.vertexCount, instances);
    }
    // A filled template's polygons, in the same unlit colour as its outline.
    if (batch.triangleVertexCount > 0) {
      gl_.BindVertexArray(whole ? batch.triangleVertexArray : batch.triangleLevelVertexArray);
      gl_.DrawArraysInstanced(GL_TRIANGLES, 0, batch.triangleVertexCount, instances);
    }
  }
}

const OrganDrawingType& plantHairDrawing() {
  static const OrganDrawingTypeOf<HairDrawing> type("hairs");
  return type;
}

}  // namespace hirsute
