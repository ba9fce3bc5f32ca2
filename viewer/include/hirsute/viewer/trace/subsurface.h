// Light that travels inside a leaf or a petal before it leaves (the hairy-plants paper's future
// work: papers/002_0e0bce38b72f21dc.txt, Sec. 5 models translucency by diffuse transmission
// alone). A random walk, as Cycles' and Mitsuba 3's random-walk subsurface scattering do,
// inside a thin sheet bounded by its two faces: a slab of the sheet's thickness, infinite
// across, about the surface the turtle drew (which has no thickness of its own).
//
// Why a walk in a slab rather than a diffusion profile: a petal is a few mean free paths
// thick, where the diffusion approximation of a semi-infinite medium (Jensen et al. 2001, the
// profiles of Christensen and Burley) is poor and knows no back face; the walk is exact for
// the slab at any thickness and gives the share reflected and the share passed through from
// one simulation. Across the sheet the walk's drift (of the order of its thickness, a fraction
// of a millimetre) is far below what the picture resolves, so light leaves where it entered, on
// the face the walk ends at: the surfaces' own triangles, veins and textures keep their places.
//
// Light enters through a rough face, diffusely (cosine-distributed, as the Lambertian lobes of
// surface_bsdf.h), takes exponential free paths of mean `meanFreePath`, scatters isotropically
// with the single-scattering albedo (a colour: each scattering keeps that share of each
// channel) and leaves through whichever face it crosses, diffusely again, so the walk is
// reciprocal. A walk longer than kMaxWalkSteps scatterings is ended and its light counted as
// absorbed: a walk across a sheet τ free paths thick takes of the order of τ² steps, and the
// view file allows τ up to 100, where a few walks in ten thousand reach the limit; with a
// single-scattering albedo below 0.999 their light is negligible anyway.
#pragma once

#include <glm/glm.hpp>

#include "hirsute/viewer/trace/sampling.h"
#include "hirsute/viewer/trace/surface_bsdf.h"

namespace hirsute::trace {

struct SubsurfaceMaterial {
  float meanFreePath = 0;  // 0: no subsurface scattering
  float thickness = 0;     // the sheet's, in the model's units
  glm::vec3 albedo{0.0f};  // single-scattering albedo, each channel in [0, 1]
  bool present() const { return meanFreePath > 0 && thickness > 0; }
};

// The scatterings a walk may take before its light counts as absorbed.
inline constexpr int kMaxWalkSteps = 10000;

// One walk's end: the face it left by (true: the far face, light passed through) and the share
// of each channel that came out.
struct SlabWalk {
  bool transmitted = false;
  glm::vec3 weight{0.0f};
  int steps = 0;  // scatterings taken
};

// A walk from the near face into the slab.
SlabWalk walkThroughSlab(const SubsurfaceMaterial& material, Random& random);

// A hit on a sheet with subsurface scattering: kWalksPerHit walks estimate the shares that
// leave by the near face and by the far one, and `surface` (the material `base` as tinted,
// textured and veined at the hit) becomes two Lambertian lobes of those shares, times what the
// hit's colour makes of the base's (the veins' and textures' ratio), so that the integrator
// samples the lights on both sides of the sheet as for its diffuse transmission. The estimates
// are unbiased and the light is linear in them, so the picture is too; several walks a hit,
// rather than one that picks a side, keep a backlit petal from the noise of that choice (the
// walks cost little beside the rays). What the specular lobe reflects does not enter.
inline constexpr int kWalksPerHit = 8;
void walkIntoSheet(const SubsurfaceMaterial& material, const SurfaceMaterial& base,
                   SurfaceMaterial& surface, Random& random);

// The single-scattering albedo that gives a thick sheet of random walks the multiple-scattering
// albedo `colour` (Chiang, Kutz and Burley 2016, "Practical and controllable subsurface
// scattering for production path tracing", their fit for the walk in a half-space), so that a
// sheet without an explicit albedo keeps its colour's hue.
glm::vec3 singleScatteringAlbedo(const glm::vec3& colour);

}  // namespace hirsute::trace
