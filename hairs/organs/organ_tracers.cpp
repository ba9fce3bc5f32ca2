// The organs' tracers (organ_tracer.h), registered (organ_list.h).
#include "hirsute/viewer/trace/organ_tracer.h"
#include "organ_list.h"

namespace hirsute {

#define HIRSUTE_DECLARE(folder, name) const trace::OrganTracer& name##Tracer();
HIRSUTE_ORGANS(HIRSUTE_DECLARE)
#undef HIRSUTE_DECLARE

namespace trace {

std::span<const OrganTracer* const> organTracers() {
#define HIRSUTE_TRACER(folder, name) &name##Tracer(),
  static const OrganTracer* const tracers[] = {HIRSUTE_ORGANS(HIRSUTE_TRACER)};
#undef HIRSUTE_TRACER
  return tracers;
}

}  // namespace trace
}  // namespace hirsute
