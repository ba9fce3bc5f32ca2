// Where derived modules go: the string writers, and later the turtle.
#pragma once

#include <cstddef>

#include "hirsute/lsys/module_string.h"

namespace hirsute {

class ModuleSink {
 public:
  virtual ~ModuleSink() = default;
  virtual void module(char symbol, const float* parameters, std::size_t count) = 0;
  // A module of a string; sinks that can copy it whole override this.
  virtual void module(ModuleRef m) {
    float values[kMaxModuleParameters];
    std::size_t count = m.parameterCount();
    for (std::size_t i = 0; i < count; ++i) values[i] = m.parameter(i);
    module(m.symbol(), values, count);
  }
  // Modules [from, to) of a string, unchanged; sinks that can walk the bytes themselves
  // override this and save a virtual call per module.
  virtual void modules(const ModuleString& s, std::size_t from, std::size_t to) {
    for (std::size_t p = from; p < to; p = s.next(p)) {
      beginSource(p);
      module(s.at(p));
    }
  }
  // Called before the modules that come from the string's module at `position` (itself, or
  // what the homomorphism made of it). The turtle's query pass uses it to find the module
  // whose parameters it fills.
  virtual void beginSource(std::size_t /*position*/) {}
};

}  // namespace hirsute
