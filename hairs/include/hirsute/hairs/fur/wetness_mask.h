// The wetness mask of a fur surface (Silva et al. 2010, Sec. 3.1, Algorithm 1): per texel of the
// surface's [0, 1]² parametrization the centre, radius and wetness of the clump it belongs to.
// The texels live in FurSurface::wetness (the Scene), so every output reads the same mask.
#pragma once

#include <glm/glm.hpp>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::fur {

// Makes the mask size² texels, all dry: a dry mask holds no texels (FurSurface::wetness is
// empty) until the first droplet falls on it.
void clearWetness(FurSurface& surface, int size);

// Blends a droplet (centre in [0, 1]², radius in those units, wetness rho in [0, 1]) into every
// texel whose centre it covers, by Algorithm 1: a texel of a clump whose centre lies within the
// droplet joins the droplet (centre and radius move towards it by rho_drop / rho_total, wetness
// adds, clamped to 1); any other texel, dry or of a clump farther away, takes the droplet's.
// (Algorithm 1 leaves a dry texel whose stored centre happens to lie within the droplet dry; a
// dry texel has no clump, so here it always takes the droplet.) On a surface that wraps in u
// (a closed cylinder), distances in u are taken around the girth.
void blendDroplet(FurSurface& surface, const glm::vec2& centre, float radius, float wetness);

// The texel holding uv (nearest; u wraps on a wrapping surface, else both clamp): (clump centre
// u, v, radius, wetness). A surface without a mask is dry.
glm::vec4 wetnessAt(const FurSurface& surface, const glm::vec2& uv);

// The difference a - b in the parametrization, u taken the short way round on a wrapping surface.
glm::vec2 parameterDifference(const FurSurface& surface, const glm::vec2& a, const glm::vec2& b);

// Drying: every texel's wetness falls by `amount` (clamped at 0); a texel that reaches 0 is dry
// and leaves its clump. Returns whether any texel is still wet.
bool dry(FurSurface& surface, float amount);

}  // namespace hirsute::fur
