// The C preprocessor's messages (what cpp writes to its standard error) read as diagnostics.
//
// cpp writes one message a line, `FILE:LINE:[COL:] (fatal error|error|warning): TEXT`, between
// lines that are none ("In file included from …", "compilation terminated."). A model writes
// TEXT itself (`#error`, `#warning`, an `#include` name) and may make it as long as it likes:
// the lines are read by plain parsing that costs no more than their length, and what is printed
// is shortened to kMaxPreprocessorMessageBytes.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

// A message's text and its file name longer than this are printed shortened in the middle.
inline constexpr std::size_t kMaxPreprocessorMessageBytes = 400;

struct PreprocessorMessage {
  std::string file;
  int line = 0;
  int column = 0;  // 0 when cpp gave none
  bool warning = false;
  std::string text;
};

// The message one line of cpp's output holds; false when the line holds none. The file name is
// the shortest prefix followed by `:LINE:[COL:] KIND: ` (a file name may hold colons); absurd
// line and column numbers (beyond nine digits) read as 0.
bool parsePreprocessorMessage(std::string_view line, PreprocessorMessage& message);

// `text` when it is at most `maxBytes` long; else its beginning and its end, `maxBytes` bytes
// together, around "…" and the number of bytes left out (the end of a message often says what
// happened: "File name too long"). Cuts fall between UTF-8 characters.
std::string shortenedMessage(std::string_view text, std::size_t maxBytes);

// Turns cpp's output `messages` into diagnostics: warnings are passed to `diagnostics`, and the
// first error is thrown as DiagnosticError, at the `#include`'s name when it names a missing or
// refused file (read beneath `folder`). When there is no error and `failure` is not empty (cpp
// failed: "exit status 1"), a DiagnosticError names `fallbackFile` and says so.
void reportPreprocessorMessages(const std::string& messages, const std::string& failure,
                                const std::string& fallbackFile,
                                const std::filesystem::path& folder, Diagnostics& diagnostics);

}  // namespace hirsute
