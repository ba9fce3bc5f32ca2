// Fur in the path tracer (organ_tracer.h): the explicit strands the exports make
// (fur_strands.h), bent, curled and clumped as the shells draw them, as round curves a strand
// thick, each of its colour at its root, shaded by the hair model.
#pragma once

#include "hirsute/viewer/trace/organ_tracer.h"

namespace hirsute {

const trace::OrganTracer& furTracer();

}  // namespace hirsute
