// The line format shared by the `.e` file and the environmental programs' specification files:
// one setting a line, its keyword everything before the first `:` or TAB (compared exactly),
// its values tokens of the rest split at a set of separator characters.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

struct KeywordToken {
  std::string text;
  int column = 0;  // 1-based, in the line
};

struct KeywordLine {
  std::shared_ptr<const std::string> file;
  int line = 0;
  std::string text;      // without the newline
  std::string keyword;   // up to the first ':' or TAB
  std::size_t rest = 0;  // offset of what follows that character (text.size() when none)

  SourceLocation at(int column) const { return SourceLocation{file, line, column}; }
  // The rest of the line after the keyword, as it is (leading blanks kept).
  std::string restText() const { return text.substr(rest); }
  // The rest split at any of `separators`; empty tokens are dropped.
  std::vector<KeywordToken> tokens(const char* separators) const;
};

// The largest environment file read (a .e or a program's specification file): real ones hold a
// few hundred bytes.
inline constexpr std::size_t kMaxKeywordFileBytes = std::size_t{1} << 20;

// Reads every line of `file`; a line longer than `maxLength` characters, a file that cannot be
// read or is no regular file (a FIFO or a device such as /dev/zero is refused at once), and one
// larger than kMaxKeywordFileBytes are errors.
std::vector<KeywordLine> readKeywordLines(const std::filesystem::path& file, std::size_t maxLength);
// The same for text already read; `file` names it in diagnostics.
std::vector<KeywordLine> keywordLines(std::string_view text, const std::filesystem::path& file,
                                      std::size_t maxLength);

// A number at the start of `token` as C's atof reads it, rounded to float (the programs keep
// f32). A token that does not begin with a number is an error at its column.
float keywordNumber(const KeywordLine& line, const KeywordToken& token);
// The same as an int, truncated as C's (int) conversion does.
int keywordInteger(const KeywordLine& line, const KeywordToken& token);

// Warns that the line's keyword is not one of the file's.
void warnUnknownKeyword(const KeywordLine& line, Diagnostics& diagnostics, const std::string& what);

}  // namespace hirsute
