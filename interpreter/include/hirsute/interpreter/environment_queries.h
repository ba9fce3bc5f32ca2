// What the turtle's query pass tells an environment about each ?E module it meets (cpfg's open
// L-systems): the turtle at that point, the module's parameters, the module after it, and where
// the ?E lies in the derived string so that the answer can be written back.
#pragma once

#include <cstddef>
#include <string>

#include "hirsute/interpreter/turtle_state.h"
#include "hirsute/lsys/module_string.h"

namespace hirsute {

struct EnvironmentQuery {
  const TurtleState* turtle = nullptr;  // the state after every module before the ?E
  const float* parameters = nullptr;    // the E module's parameters
  std::size_t count = 0;
  // The position of the E module in the string of the pass, or kMadeByHomomorphism for a ?E
  // that a homomorphism production made (cpfg sends it, and ignores its answer).
  static constexpr std::size_t kMadeByHomomorphism = static_cast<std::size_t>(-1);
  std::size_t position = kMadeByHomomorphism;
  // The module that follows the ?E: empty symbols when there is none. `~` and `@` take the next
  // character too (`@O(1)` is "@O" with the O's parameters).
  std::string followingSymbols;
  const float* followingParameters = nullptr;
  std::size_t followingCount = 0;
};

// The environment's side of the query pass: beginPass before the turtle walks the string,
// query for every ?E in interpretation order, endPass when the walk is over (the environment
// answers then and writes into `string`).
class EnvironmentQueries {
 public:
  virtual ~EnvironmentQueries() = default;
  virtual void beginPass(ModuleString& string, int step) = 0;
  virtual void query(const EnvironmentQuery& q) = 0;
  virtual void endPass() = 0;
};

}  // namespace hirsute
