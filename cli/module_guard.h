// What a module's entry point (drawing_module.cpp, trace_module.cpp) runs its command in: nothing
// is thrown across the module's boundary; an exception becomes a message and an exit code.
#pragma once

#include <exception>
#include <iostream>
#include <new>

#include "command.h"

namespace hirsute::cli {

template <class Options, class Run>
int guarded(const Options* options, Run run) {
  try {
    return run(*options);
  } catch (const std::bad_alloc&) {
    std::cerr << outOfMemoryMessage() << '\n';
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "hirsute: error: " << e.what() << '\n';
    return kExitIoError;
  }
}

}  // namespace hirsute::cli
