// libFuzzer target: arbitrary bytes as a view file (`.v`) as the C preprocessor hands it on
// (with or without its `# n "file"` line markers), through both of its readers: parseViewFile
// (every command, the organs' lines, the dynamics …: lines)
// and readViewFunctions (function:, function set: and curve:, whose files are loaded).
//
// The text is read as models/herb/fuzz.v, so that its file names can name the model's real
// files (read, never written). A DiagnosticError is the expected answer to broken input;
// anything else (another exception, a crash, a sanitizer report, a hang, memory beyond
// libFuzzer's limit) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_folder.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/function_curve.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path kFile = hirsute::fuzz::modelFolder("herb") / "fuzz.v";
  const std::string text(reinterpret_cast<const char*>(data), size);
  hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
  try {
    hirsute::parseViewFile(text, kFile, diagnostics);
  } catch (const hirsute::DiagnosticError&) {
  }
  try {
    hirsute::readViewFunctions(text, kFile);
  } catch (const hirsute::DiagnosticError&) {
  }
  return 0;
}
