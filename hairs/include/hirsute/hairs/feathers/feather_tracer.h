// Feathers in the path tracer (organ_tracer.h): each feather built as the POV-Ray export builds it
// (feather_buffers.h, one level finer than the picture asks for), the shafts as smooth triangles,
// polyline barbs as flat curves turned to each ray and strip barbs as triangles, both with the
// colour and the transparency that fades to the barb tips (Sec. 4.3.1), as drawn in GL. Barbs
// are fibres: the hair model shades them along their length.
#pragma once

#include "hirsute/viewer/trace/organ_tracer.h"

namespace hirsute {

const trace::OrganTracer& featherTracer();

}  // namespace hirsute
