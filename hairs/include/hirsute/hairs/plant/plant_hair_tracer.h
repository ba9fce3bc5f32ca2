// The plant hairs in the path tracer (organ_tracer.h): each hair's template polylines as round
// curves of the hair's radius, one set of curves a template, shaded by the hair model. A hair
// the picture shows small is traced in a coarser form of its template, within a quarter of a
// pixel of it (docs/trace.md, "Hairs seen small").
#pragma once

#include <cstddef>
#include <vector>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/viewer/trace/organ_tracer.h"

namespace hirsute {

const trace::OrganTracer& plantHairTracer();

// How far a hair's traced form may stray from its template, in pixels where the hair stands.
inline constexpr float kHairStrayPixels = 0.25f;

// A template's coarser forms: form k keeps every 2^k-th vertex of each polyline and its last,
// down to one segment a polyline. `stray[k]` is the farthest a vertex it drops lies from it, in
// hair lengths (form 0 is the template: 0).
struct HairForms {
  std::vector<float> stray;
};

HairForms hairFormsOf(const HairTemplate& hair);

// The coarsest form that keeps a hair of `length` within `tolerance` (world units) of its template.
std::size_t hairFormFor(const HairForms& forms, float length, float tolerance);

// The vertices form `form` keeps of a polyline of `count` vertices, in order.
std::vector<std::size_t> keptVertices(std::size_t count, std::size_t form);

}  // namespace hirsute
