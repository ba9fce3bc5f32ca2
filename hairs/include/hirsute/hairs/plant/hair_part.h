// The plant hairs' part of the Scene (organ_part.h; docs/design.md, "Plant hairs"): the records
// the @H modules make, the template hairs of the view file's `hair:` lines, and the placed hairs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "hirsute/hairs/plant/hair_attributes.h"
#include "hirsute/interpreter/organ_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

// A template hair (docs/design.md, "Plant hairs"): the turtle positions of a small L-system,
// stored once, in the hair's own frame: x along its first segment (the hair direction), y the
// second axis (the turtle's initial left, made orthogonal), z = x × y. The root is the origin.
struct HairTemplate {
  std::string file;                               // the `hair:` line's file
  std::vector<std::vector<glm::vec3>> polylines;  // connected runs of turtle positions
  // The filled polygons of the template's `{ }` (cpfg draws a polygon filled), three vertices a
  // triangle, in the same frame and colour: a scale's blade, whose outline the polylines draw.
  std::vector<glm::vec3> triangles;
  int material = 0;                               // the colour of the template's first segment
  float extent = 0;                               // the largest distance of a vertex from the root

  std::size_t segmentCount() const {
    std::size_t n = 0;
    for (const auto& p : polylines) n += p.size() > 1 ? p.size() - 1 : 0;
    return n;
  }
};

// A placed hair: an instance of a template, not a copy (32 bytes). The template's vertex p
// lands at root + length · (orientation · p); the radius is constant along the hair.
struct Hair {
  glm::vec3 root{0.0f};
  std::array<std::int16_t, 4> orientation{0, 0, 0, 32767};  // unit quaternion (x, y, z, w), snorm16
  float length = 1;
  float radius = 0;
  std::uint8_t templateIndex = 0;
  HairSide side = HairSide::Front;
  std::uint16_t reserved = 0;

  glm::quat rotation() const {
    const glm::quat q(orientation[3] / 32767.0f, orientation[0] / 32767.0f,
                      orientation[1] / 32767.0f, orientation[2] / 32767.0f);
    return glm::normalize(q);
  }
  void setRotation(const glm::quat& q) {
    const glm::quat n = glm::normalize(q);
    auto pack = [](float c) {
      return static_cast<std::int16_t>(std::lround(glm::clamp(c, -1.0f, 1.0f) * 32767.0f));
    };
    orientation = {pack(n.x), pack(n.y), pack(n.z), pack(n.w)};
  }
  glm::vec3 direction() const { return rotation() * glm::vec3(1, 0, 0); }
  // Where template vertex p of this hair lies.
  glm::vec3 place(const glm::vec3& p) const { return root + length * (rotation() * p); }
};
static_assert(sizeof(Hair) == 32,
              "a placed hair stays 32 bytes (docs/design.md: bytes per placed hair)");

struct HairPart : OrganPartOf<HairPart> {
  std::vector<HairAttributes> attributes;  // the records segments and surfaces refer to
  std::vector<HairTemplate> templates;     // Hair::templateIndex indexes them
  std::vector<Hair> hairs;

  // Each hair's root widened by the reach of its template.
  void addBounds(Bounds& box) const override;
};

}  // namespace hirsute
