// Where derived modules go: the string writers, and later the turtle.
#pragma once

#include <cstddef>

namespace hirsute {

class ModuleSink {
 public:
  virtual ~ModuleSink() = default;
  virtual void module(char symbol, const float* parameters, std::size_t count) = 0;
};

}  // namespace hirsute
