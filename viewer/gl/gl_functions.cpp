#include "hirsute/viewer/gl/gl_functions.h"

#include <stdexcept>
#include <string>

namespace hirsute {

GlFunctions::GlFunctions(const GetProcAddress& resolve) {
#define HIRSUTE_GL_RESOLVE(type, name)                \
  name = reinterpret_cast<type>(resolve("gl" #name)); \
  if (!name) throw std::runtime_error("the GL context has no gl" #name);
  HIRSUTE_GL_FUNCTIONS(HIRSUTE_GL_RESOLVE)
#undef HIRSUTE_GL_RESOLVE
}

}  // namespace hirsute
