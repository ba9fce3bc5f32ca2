// The organs' tracers, registered: one line an organ (organ_tracer.h).
#include "hirsute/hairs/feathers/feather_tracer.h"
#include "hirsute/hairs/fur/fur_tracer.h"
#include "hirsute/hairs/plant/plant_hair_tracer.h"
#include "hirsute/viewer/trace/organ_tracer.h"

namespace hirsute::trace {

std::span<const OrganTracer* const> organTracers() {
  static const OrganTracer* const tracers[] = {
      &plantHairTracer(),
      &featherTracer(),
      &furTracer(),
  };
  return tracers;
}

}  // namespace hirsute::trace
