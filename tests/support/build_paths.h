// Where a test finds the source tree and the programs this build made. The paths are found when
// the test runs, from where the test program lies in the build folder (BUILD/tests/NAME), not
// compiled into the tests: so that the compiled tests of a clone elsewhere on the machine (as CI
// makes) are the same files and come from the compiler cache. tests/CMakeLists.txt includes this
// header in every test and defines HIRSUTE_SOURCE_DIR, HIRSUTE_BINARY and the like as calls.
#pragma once

namespace hirsute::testing {

// The source tree (the folder of the top CMakeLists.txt).
const char* sourceDir();
// A file or folder of this build, by its path relative to the build folder ("cli/hirsute").
const char* buildFile(const char* relative);

}  // namespace hirsute::testing
