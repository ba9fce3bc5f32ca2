// The feathers' part of the Scene (organ_part.h; docs/design.md, "Feathers"): the types of the view
// file's `feather:` lines, the records the @F modules make, the feathers to draw, how the
// dynamics bent them, and the box that holds their geometry.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/hairs/feathers/feather_attributes.h"
#include "hirsute/hairs/feathers/feather_type.h"
#include "hirsute/interpreter/organ_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

// Where a feather comes from: one at the turtle (@Fe, @Fi) or a coat on a surface (@Ff, @Fb).
enum class FeatherOrigin : std::uint8_t { Single, Coat };

// A feather to draw (docs/design.md, "Feathers"): an instance of the model's feather types, blended
// and grown, not a copy of geometry; every output builds the geometry from the type at its own
// level of detail (hirsute/hairs/feathers/feather_geometry.h). The frame is the turtle's at the
// feather: the calamus base at `position`, the rachis along `heading`, the front towards `up`,
// the left vane towards left() = H × U; (up, left, heading) is the geometry's (x, y, z).
struct Feather {
  glm::vec3 position{0.0f};
  glm::vec3 heading{0, 1, 0};  // unit
  glm::vec3 up{0, 0, 1};       // unit, perpendicular to heading
  float age = 1;               // 0 to 1 (1: grown), Streit & Heidrich 2002, Sec. 4.2.4
  float size = 1;              // scales every length of the type
  // The type is the bilinear blend of four (Sec. 4.2.3, 4.4): types[0] to types[1] by across[0],
  // types[2] to types[3] by across[1], and the first of those to the second by along. Types are
  // 1-based, the view file's `feather:` lines in order; @Fe(k) has all four k, @Fi(k1, k2, t)
  // {k1, k2, k1, k2} with across t.
  std::array<std::uint16_t, 4> types{1, 1, 1, 1};
  std::array<float, 2> across{0.0f, 0.0f};
  float along = 0;
  FeatherOrigin origin = FeatherOrigin::Single;

  // The turtle's left vector, where the left vane lies: L = H × U as the turtle keeps it.
  glm::vec3 left() const { return glm::cross(heading, up); }
};

// A feather bent by the feather-coat dynamics (hairs/dynamics/, `hirsute simulate`): the nodes
// of its stem, each a map from the feather's local frame (x front, y left, z rachis, as
// featherToWorld takes it) to the world, at the rest height of the node along the rachis. A
// local point at height z between the nodes i and i + 1 is mapped by both and blended linearly
// in z; below the first node and above the last, by that node alone. At rest every map is the
// feather's own frame.
struct FeatherPose {
  std::vector<float> heights;      // the nodes' local z, increasing
  std::vector<glm::mat4> toWorld;  // one per node: local to world
};

struct FeatherPart : OrganPartOf<FeatherPart> {
  // Type k of the view file's `feather:` lines is types[k - 1].
  std::vector<FeatherType> types;
  std::vector<FeatherAttributes> attributes;  // the coat records segments refer to
  // In drawing order: a coat from its bottom feather to its top one (Sec. 4.4).
  std::vector<Feather> feathers;
  // Empty, or one per feather: how the dynamics bent it (empty heights: drawn by its frame).
  std::vector<FeatherPose> poses;
  Bounds bounds;  // what the feathers' geometry fills (the feather stage measures it)
  // The outputs build each feather at the detail of its size in their picture; more vertices
  // than this in the feathers' geometry are an error (the run's --max-vertices).
  std::size_t maxVertices = kDefaultMaxVertices;
  // Every barb of every feather, each built whole (--full-feathers): the GL drawing does not thin
  // the barbs to the picture and the POV-Ray export writes no instances.
  bool fullDetail = false;

  void addBounds(Bounds& box) const override { box.add(bounds); }
};

}  // namespace hirsute
