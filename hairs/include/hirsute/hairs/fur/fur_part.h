// The fur's part of the Scene (organ_part.h; docs/design.md, "Fur"): the records the @U modules
// make, the surfaces the fur stage covers with shells, and the fur textures they share.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/hairs/fur/fur_attributes.h"
#include "hirsute/interpreter/organ_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

// A surface covered with shell fur (docs/design.md, "Fur"; Silva et al. 2010): its triangles as the
// fur stage (hairs/fur/) gathered them from a covered generalized cylinder, bicubic surface or
// polygon, each vertex with its surface frame and two parametrizations: `uv` in [0, 1]² over the
// whole surface, where the wetness mask lies (cylinders: around the girth and along the axis),
// and `texcoords` in tiles of the fur texture, which repeats and keeps strands round in world
// units. Indices are triangles, counter-clockwise seen from the side the fur grows on.
struct FurSurface {
  int attributes = -1;  // index into FurPart::attributes
  int material = 0;     // the surface's colour, when the attributes name no texture
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // unit, the side the fur grows on
  std::vector<glm::vec3> tangents;  // unit, along u, perpendicular to the normal
  std::vector<glm::vec2> uv;
  std::vector<glm::vec2> texcoords;  // = uv · texcoordsPerUv
  glm::vec2 texcoordsPerUv{1.0f};
  std::vector<std::uint32_t> indices;
  bool wrapsU = false;     // a closed cylinder: u = 0 and u = 1 are one line of the surface
  float area = 0;          // world units²
  int furTexture = 0;      // index into FurPart::textures
  int layers = 16;         // N, the view file's `fur layers:`
  float strandRadius = 0;  // half a texel of the fur texture, world units
  // The strands' particles p (Sec. 3.2.1), one per vertex: where the tip of the strand rooted
  // there is (at rest p_0 = position + length · normal). The fur stage leaves them at rest under
  // the view file's force; the viewer steps them.
  std::vector<glm::vec3> tips;
  // The wetness mask (Sec. 3.1): wetnessSize² texels, row v, column u, each (clump centre u,
  // clump centre v, clump radius, wetness rho); rho = 0 is dry. A mask no droplet has touched
  // holds no texels (`wetness` empty): the whole surface is dry.
  int wetnessSize = 0;
  std::vector<glm::vec4> wetness;

  std::size_t triangleCount() const { return indices.size() / 3; }
};

// The fur geometry texture (Sec. 4; Papaioannou 2002): size² texels, each 0 (no strand) or the
// length of the strand rooted there, in 255ths of the fur length. Strands are a texel thick;
// layer h of the shells shows the texels whose strand reaches h.
struct FurTexture {
  int size = 0;
  float density = 0;  // the fill it was made for: strands per texel
  std::vector<std::uint8_t> lengths;
};

struct FurPart : OrganPartOf<FurPart> {
  std::vector<FurAttributes> attributes;  // the records surfaces refer to
  std::vector<FurSurface> surfaces;
  std::vector<FurTexture> textures;
  // The exports and the tracer build every strand's points; more than this in all is an error
  // (the run's --max-vertices, set by the fur stage).
  std::size_t maxVertices = kDefaultMaxVertices;

  // Every surface vertex widened by the fur's length.
  void addBounds(Bounds& box) const override;
};

}  // namespace hirsute
