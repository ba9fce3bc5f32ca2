// Running a piece of work where its crash, spin or appetite cannot take the program down: in a
// forked child process of its own process group, with a memory limit (RLIMIT_AS), a processor
// time limit (RLIMIT_CPU), no core file and a wall-clock limit after which its whole group is
// killed. The child may be confined to reading beneath a folder (child_confinement.h). The work
// returns bytes, which come back over a pipe; the caller decodes them, as bytes from an
// untrusted source (a child that a malformed file took over may send anything).
//
// A library with bugs of its own reads hostile files this way: Hirsute's mesh reader runs Assimp
// so (mesh_file.h), and a file that crashes Assimp or makes it loop becomes an error message.
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>

namespace hirsute {

struct IsolatedCallLimits {
  // Address space the child may add to what it inherits; 0: no limit. Not applied in a build
  // with AddressSanitizer, whose shadow memory needs address space of its own.
  std::size_t memoryBytes = 0;
  // Wall-clock time; the processor time limit is the same, rounded up to a second.
  std::chrono::milliseconds time{60'000};
  // When not empty, the child reads files only beneath this folder (and the system's libraries),
  // where the kernel has Landlock, and writes none.
  std::filesystem::path readableFolder;
  // The most bytes the work may return; more is a failure.
  std::size_t maxOutputBytes = std::size_t(1) << 32;
};

struct IsolatedCallResult {
  enum class End {
    Finished,     // the work returned; `output` holds its bytes
    OutOfMemory,  // the work threw std::bad_alloc (it reached the memory limit)
    TimedOut,     // the time limit passed (wall clock or processor time); the group was killed
    Crashed,      // the child ended on a signal (`signal`)
    Failed,       // the child could not be started, threw, or ended without its whole output
  };
  End end = End::Failed;
  std::string output;
  int signal = 0;
  std::string why;  // for Failed: what went wrong, in words
};

// Runs `work` in a child process under `limits` and waits for it. Never throws for what the
// child does; throws std::system_error when no child can be made (no pipe, no fork).
IsolatedCallResult callIsolated(const std::function<std::string()>& work,
                                const IsolatedCallLimits& limits);

// A signal's name for a message: "segmentation fault", "abort", …
std::string signalDescription(int signal);

}  // namespace hirsute
