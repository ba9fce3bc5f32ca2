// The plant hairs in the path tracer (organ_tracer.h): each hair's template polylines as round
// curves of the hair's radius, one set of curves a template, shaded by the hair model.
#pragma once

#include "hirsute/viewer/trace/organ_tracer.h"

namespace hirsute {

const trace::OrganTracer& plantHairTracer();

}  // namespace hirsute
