// libFuzzer target: arbitrary bytes as the C preprocessor's messages (what cpp writes to its
// standard error), read back into diagnostics (lsys/preprocessor_messages.h): each line parsed,
// warnings passed on, the first error thrown, missing and refused `#include` names looked up
// in the file the message names.
//
// A model writes much of that text itself (`#error`, `#warning`, `#include` names, `#line` file
// names) at any length, so every line must be read in time proportional to its length and
// printed shortened. The folder is tests/bad_input (read, never written), whose files the seeds'
// messages name. A DiagnosticError is the expected answer; anything else (another exception, a
// crash, a sanitizer report, a hang) is a bug, and so is a printed message far longer than the
// limit.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/preprocessor_messages.h"

namespace {

// A message's text, shortened, and what a diagnostic adds to it (the count of bytes left out,
// the note on a denied #include, "the C preprocessor failed (…)").
constexpr std::size_t kMaxPrintedBytes = hirsute::kMaxPreprocessorMessageBytes + 200;

void checkPrinted(const std::string& text) {
  if (text.size() > kMaxPrintedBytes) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path kFolder =
      std::filesystem::path(HIRSUTE_SOURCE_DIR) / "tests" / "bad_input";
  const std::string messages(reinterpret_cast<const char*>(data), size);

  // Every line on its own: a message found keeps the whole line's text.
  hirsute::PreprocessorMessage message;
  for (std::size_t start = 0; start <= messages.size();) {
    std::size_t end = messages.find('\n', start);
    if (end == std::string::npos) end = messages.size();
    const std::string_view line(messages.data() + start, end - start);
    if (hirsute::parsePreprocessorMessage(line, message) &&
        message.file.size() + message.text.size() > line.size()) {
      std::abort();
    }
    start = end + 1;
  }

  // The whole text, as the run reports it, once as from a failed cpp and once as from one that
  // succeeded with warnings.
  for (const char* failure : {"exit status 1", ""}) {
    hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
    try {
      hirsute::reportPreprocessorMessages(messages, failure, (kFolder / "fuzz.l").string(), kFolder,
                                          diagnostics);
    } catch (const hirsute::DiagnosticError& e) {
      checkPrinted(e.diagnostic().message);
    }
    for (const hirsute::Diagnostic& warning : diagnostics.warnings()) {
      checkPrinted(warning.message);
    }
  }
  return 0;
}
