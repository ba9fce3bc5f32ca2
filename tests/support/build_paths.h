// Where a test finds the source tree and the programs this build made. The paths are found when
// the test runs, from where the test program lies in the build folder (BUILD/tests/NAME), not
// compiled into the tests: so that the compiled tests of a clone elsewhere on the machine (as CI
// makes) are the same files and come from the compiler cache. tests/CMakeLists.txt includes this
// header in every test (hirsute_test_paths), which so has HIRSUTE_SOURCE_DIR, HIRSUTE_BINARY and
// the like below.
#pragma once

namespace hirsute::build_paths {

// The source tree (the folder of the top CMakeLists.txt).
const char* sourceDir();
// A file or folder of this build, by its path relative to the build folder ("cli/hirsute").
const char* buildFile(const char* relative);

}  // namespace hirsute::build_paths

#define HIRSUTE_SOURCE_DIR (::hirsute::build_paths::sourceDir())
#define HIRSUTE_BINARY (::hirsute::build_paths::buildFile("cli/hirsute"))
#define HIRSUTE_PLUS_ONE (::hirsute::build_paths::buildFile("tests/hirsute_env_plus_one"))
#define HIRSUTE_MISBEHAVING (::hirsute::build_paths::buildFile("tests/hirsute_env_misbehaving"))
#define HIRSUTE_ENVIRONMENT_SERVER \
  (::hirsute::build_paths::buildFile("environment/hirsute-environment"))
#define HIRSUTE_COMM_LIBRARY_DIR (::hirsute::build_paths::buildFile("environment"))
