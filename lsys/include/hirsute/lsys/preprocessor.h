// The C preprocessor pass that cpfg runs over `.l` and `.v` files.
//
// cpfg pipes its input through GNU cpp with C++ comments enabled and keeps the `# line "file"`
// markers, so every later message can point into the user's own file. We run Debian's `cpp` in
// traditional mode, which passes cpfg's module text through untouched (quotes, `#(w)` after
// indentation, `\\` roll modules), after a pass of our own that does what traditional mode lacks:
// `//` comments are removed and indented directives are moved to column 1.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

// The preprocessed text's limit unless raised (--max-source-bytes): 16 MiB.
inline constexpr std::size_t kDefaultMaxSourceBytes = std::size_t{16} << 20;

struct PreprocessorOptions {
  // Object-like macros defined before the file is read (cpfg: `function set:` names of the .v).
  std::vector<std::pair<std::string, std::string>> defines;
  // The preprocessor program; `cpp` on the PATH by default.
  std::string program = "cpp";
  // Limits of one run: the preprocessed text (an #include of itself twice per level doubles it
  // at every level; the parsed program takes about a hundred bytes a byte of it), which sets the
  // memory too (preprocessorMemoryLimit), and the wall-clock time (an #include of a FIFO that a
  // macro names waits for its writer).
  std::size_t maxOutputBytes = kDefaultMaxSourceBytes;
  int timeoutSeconds = 60;
};

// The C preprocessor's memory (its address space, RLIMIT_AS): 64 times the preprocessed text's
// limit, at least 128 MiB; 1 GiB by default. A macro that doubles at every level needs it all
// before cpp writes a byte.
std::size_t preprocessorMemoryLimit(std::size_t maxOutputBytes);

// The preprocessed text with line markers, ready for a lexer that understands them.
// Throws DiagnosticError with the location of the problem in the user's file. An `#include` of a
// FIFO, socket or device (beneath the model's folder) is refused at its directive before cpp
// runs; cpp runs in a process group of its own, ended as a whole when it is done or stopped.
std::string preprocessFile(const std::filesystem::path& file, const PreprocessorOptions& options,
                           Diagnostics& diagnostics);
// The same for `text` standing in for the file's contents (the viewer's `#define` panel and
// `simulate --animate` change a constant without writing a copy of the file): messages name
// `file`, and includes are found beside it.
std::string preprocessText(const std::string& text, const std::filesystem::path& file,
                           const PreprocessorOptions& options, Diagnostics& diagnostics);

// Removes `//` comments (outside strings and `/* */` comments) and moves indented
// preprocessor directives to column 1; the number of lines is unchanged.
std::string prepareForTraditionalCpp(const std::string& text);

}  // namespace hirsute
