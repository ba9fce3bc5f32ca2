// libFuzzer target: arbitrary bytes as a feather type file (`.fea`, docs/feathers.md, "The
// feather file") through parseFeatherType, the reader loadFeatherType goes through, and a type
// it accepts built into its geometry at the lowest level of detail.
//
// The text is read as models/feather-parameters/fuzz.fea, so that an `afterfeather:` or
// `texture:` line can name the model's real files (read, never written). A DiagnosticError is
// the expected answer to broken input; anything else (another exception, a crash, a sanitizer
// report, a hang, memory beyond libFuzzer's limit) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_folder.h"
#include "hirsute/hairs/feathers/feather_file.h"
#include "hirsute/hairs/feathers/feather_geometry.h"
#include "hirsute/core/diagnostic.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path kFile =
      hirsute::fuzz::modelFolder("feather-parameters") / "fuzz.fea";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
  try {
    const hirsute::FeatherType type = hirsute::parseFeatherType(text, kFile, diagnostics);
    hirsute::FeatherDetail lowest;
    lowest.rachisSegments = lowest.barbSegments = lowest.shaftSides = 3;
    hirsute::buildFeatherGeometry(type, lowest);
  } catch (const hirsute::DiagnosticError&) {
  }
  return 0;
}
