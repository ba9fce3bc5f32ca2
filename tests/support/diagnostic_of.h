// Tests of errors: the diagnostic a load throws.
#pragma once

#include <gtest/gtest.h>

#include "hirsute/core/diagnostic.h"

namespace hirsute::testing {

// Runs `load` and returns the diagnostic it throws; fails the test when it throws none.
template <typename Load>
Diagnostic diagnosticOf(Load load) {
  try {
    load();
  } catch (const DiagnosticError& error) {
    return error.diagnostic();
  }
  ADD_FAILURE() << "expected a DiagnosticError";
  return Diagnostic{};
}

}  // namespace hirsute::testing
