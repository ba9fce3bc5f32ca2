// The vertex data of a Scene's feathers, as the GL renderer draws them (Streit & Heidrich 2002,
// Sec. 4.3): every feather built from its type at the level of detail its size on the screen
// asks for (Sec. 4.3, Fig. 8), in world coordinates, and the order in which its barbs are drawn
// for a camera (Sec. 4.3.1). GL-free, so that it can be measured and tested without a context.
//
// Shafts are opaque, lit triangles. Barbs are unlit polylines (GL lines) or two triangle strips
// either side (the type's `drawing:`), their alpha fading to 0 at the barb tip and, for strips,
// across the strip away from the barb; they are blended, so their order matters: a coat from its
// bottom feather to its top one (the Scene keeps feathers in that order), and within a feather
// the vane farther from the eye first, its barbs from the rachis out, then the nearer vane, its
// barbs from the tip in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

struct FeatherBuffers {
  // Shafts (calamus and rachis tubes), every feather's afterfeathers included.
  std::vector<glm::vec3> shaftPositions;
  std::vector<glm::vec3> shaftNormals;
  std::vector<glm::vec3> shaftColors;
  std::vector<std::uint32_t> shaftIndices;  // triangles

  // Barb vertices: position, colour with alpha, texture coordinates of the type's mapping.
  std::vector<glm::vec3> barbPositions;
  std::vector<glm::vec4> barbColors;
  std::vector<glm::vec2> barbTexcoords;

  // A run of barb primitives (GL_LINES pairs, or triangles for strips) of one vane, its
  // primitives listed from the rachis out; `texture` is the Scene texture it is drawn with (-1
  // none), `triangles` whether they are strips.
  struct Vane {
    std::uint32_t first = 0, count = 0;  // into vaneIndices
    std::uint32_t primitiveSize = 2;     // 2 (lines) or 3 (triangles)
    std::uint32_t perBarb = 0;           // primitives a barb (its barbs have equal segments)
    int texture = -1;
    // Its colours vary vertex by vertex: a blended type's cross-fade of textures, drawn into
    // them (FeatherAppearance::crossFade); `texture` is then -1.
    bool faded = false;
    bool left = true;
    // Where the same primitives stand from the tip in, the nearer vane's order (Sec. 4.3.1):
    // filled by buildFeatherInstances only, which keeps both orders in vaneIndices.
    std::uint32_t tipInwardFirst = 0;
  };
  std::vector<std::uint32_t> vaneIndices;
  // Per feather part (a feather and each of its afterfeathers): its two vanes and where it is.
  struct Part {
    Vane vanes[2];
    glm::vec3 position{0.0f};  // the calamus base
    glm::vec3 left{0.0f};      // the left vane's side
  };
  std::vector<Part> parts;
  // The detail level each feather was built at (featherDetailLevel), to tell when to rebuild.
  std::vector<std::uint8_t> levels;

  std::size_t barbCount = 0;
  std::size_t barbSegments = 0;
  std::size_t shaftTriangles() const { return shaftIndices.size() / 3; }
  std::size_t byteSize() const;
};

// Quantised level of detail for a feather whose length covers `pixels` on the screen: levels
// step by a factor of two, so zooming rebuilds feathers only when their size doubles or halves.
int featherDetailLevel(float pixels);

// How many pixels the feather's length covers for `camera` (a sphere of its length around its
// middle, projected).
float featherScreenLength(const Scene& scene, const Feather& feather, const Camera& camera);

// The levels `camera` asks for, one per feather.
std::vector<std::uint8_t> featherDetailLevels(const Scene& scene, const Camera& camera);

// Builds every feather of `scene` at its level.
FeatherBuffers buildFeatherBuffers(const Scene& scene, const std::vector<std::uint8_t>& levels);

// Each barb vertex's colour (display values) times its vane's texture there, with its alpha, as
// GL's barb shader multiplies them: what the outputs that colour barbs by vertex (the tracer,
// POV-Ray) draw.
std::vector<glm::vec4> texturedBarbColours(const Scene& scene, const FeatherBuffers& buffers);

// A Scene's feathers as instances of templates (docs/design.md, "Feathers"; hot data laid out as
// instances of templates): feathers that share their key types, blend weights, age and level of
// detail are built once, in their own frame (feather_geometry.h), and placed by a transform
// each, so that a coat's memory follows the types and sizes in the picture, not its feather
// count. The weights and the age are rounded to steps of 2 pixels of the feather's length in the
// picture, at least 1/32 (feather_buffers.cpp): rounding moves a feather's outline by at most a
// pixel where its key types' lengths differ by at most its length, and its colour by at most
// 1/64 of its key types' difference (docs/feathers.md, "Dense coats"). A feather the dynamics bent
// (FeatherPart::poses) is a template of its own, built in the world.
struct FeatherInstances {
  // Every template's geometry, one after another; each vane's barbs from the rachis out at
  // Vane::first and from the tip in at Vane::tipInwardFirst.
  FeatherBuffers geometry;
  struct Template {
    std::uint32_t firstPart = 0, partCount = 0;                // into geometry.parts
    std::uint32_t firstShaftIndex = 0, shaftIndexCount = 0;    // into geometry.shaftIndices
    std::uint32_t firstShaftVertex = 0, shaftVertexCount = 0;  // into the geometry's arrays
    std::uint32_t firstBarbVertex = 0, barbVertexCount = 0;
    std::size_t vertices = 0;    // shaft and barb vertices
    std::size_t primitives = 0;  // shaft triangles, barb primitives
    int barbStride = 1;          // every barbStride-th barb (thinned; feather_geometry.h)
  };
  std::vector<Template> templates;
  std::vector<std::uint32_t> templateOf;  // per feather, in the Scene's order
  std::vector<glm::mat4> toWorld;         // per feather: its template's frame to the world
  std::vector<std::uint8_t> levels;       // as FeatherBuffers::levels
  std::size_t drawnVertices = 0;          // every instance's template vertices
  std::size_t byteSize() const;
};

// The feathers of `scene` as instances at `levels` (featherDetailLevels), thinned to the
// picture (thinnedFeatherDetail); with `fullDetail` (--full-feathers) every barb, and templates
// only for feathers exactly alike. The drawn geometry, every instance's vertices, counts against
// FeatherPart::maxVertices (a GeometryLimitError).
FeatherInstances buildFeatherInstances(const Scene& scene, const std::vector<std::uint8_t>& levels,
                                       bool fullDetail);

// A run of barb indices drawn with one texture, in drawing order.
struct FeatherDrawRun {
  int texture = -1;
  bool triangles = false;
  std::uint32_t first = 0, count = 0;  // into the index list
};

// The barb index list in drawing order for an eye at `eye` (perspective) or looking along
// `forward` (parallel), and its runs by texture and primitive.
void orderFeatherBarbs(const FeatherBuffers& buffers, const Camera& camera,
                       std::vector<std::uint32_t>& indices, std::vector<FeatherDrawRun>& runs);

}  // namespace hirsute
