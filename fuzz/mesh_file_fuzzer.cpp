// libFuzzer target: arbitrary bytes as a mesh file through the mesh reader (mesh_file.h) with
// its checks of the bytes before Assimp (mesh_file_checks.h), in this process
// (MeshReading::InProcess), so that a crash inside Assimp that the checks let through is a
// finding here; the program itself reads meshes in a child process, where such a crash becomes
// an error message.
//
// The first byte picks the format (its value modulo 7: PLY, OBJ, glTF, GLB, STL, OFF, COLLADA),
// that is the file's extension, as Assimp chooses its importer by it; the rest is the file,
// written into a private folder (fuzz_folder.h) and read beneath it. A DiagnosticError is the
// expected answer to broken input; anything else (another exception, a crash, a sanitizer
// report, a hang, memory beyond libFuzzer's limit) is a bug.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "fuzz_folder.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/mesh_file.h"

// Assimp (Debian's, not instrumented) leaks what it allocated when it gives up on a broken file;
// those leaks are no finding (the program reads meshes in a child process, whose memory ends with
// it), and the leak check at exit is off. Crashes, hangs and memory errors still are findings.
extern "C" const char* __asan_default_options() {
  return "detect_leaks=0";
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const hirsute::fuzz::FuzzFolder folder("mesh_file_fuzzer");
  static const char* const kExtensions[] = {".ply", ".obj", ".gltf", ".glb",
                                            ".stl", ".off", ".dae"};
  if (size == 0) return 0;
  const std::filesystem::path file =
      folder.path() / (std::string("fuzz") + kExtensions[data[0] % 7]);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
  try {
    // A small triangle limit keeps each input fast; the checks count before Assimp reads.
    hirsute::loadMeshFile(file, folder.path(), 20'000, diagnostics,
                          hirsute::MeshReading::InProcess);
  } catch (const hirsute::DiagnosticError&) {
  }
  std::filesystem::remove(file);
  return 0;
}
