// The lines of a preprocessed cpfg view file (.v) as cpfg's ReadViewData splits them: a label up
// to and including the first ':', then the arguments. Shared by every reader of the view file
// (the function and curve lines here in lsys, all other commands in the interpreter), so that
// labels and line numbers are found one way.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

// One non-blank line of the view file. The views point into the text given to viewFileLines,
// which must outlive them.
struct ViewFileLine {
  SourceLocation where;    // the user's file and line (column 0), after the cpp line markers
  std::string_view label;  // cpfg: from the first non-space character (tabs are not skipped) up
                           // to and including the first ':'; empty when the line has no ':'
  std::string_view rest;   // everything after the label (the whole line when there is none)
  int restColumn = 1;      // 1-based column of rest's first character

  // The location of a character of `rest` given by its offset into it.
  SourceLocation at(std::size_t restOffset) const;
};

// A word of a line and where it starts.
struct ViewWord {
  std::string_view text;
  int column = 0;  // 1-based
};

// The non-blank lines of a view file as the preprocessor leaves it. Line numbers and file names
// follow the `# n "file"` markers, so they point into the user's own file (and into files it
// includes). `viewFile` names the lines before the first marker.
std::vector<ViewFileLine> viewFileLines(std::string_view preprocessedText,
                                        const std::filesystem::path& viewFile);

// The whitespace-separated words of a line's `rest`, with their columns.
std::vector<ViewWord> viewWords(const ViewFileLine& line);

// A cpp line marker `# 12 "plant.v" 1` or `#line 12 "plant.v"`: the number of the next line and
// the file it comes from (empty when the marker names none).
std::optional<std::pair<int, std::string>> lineMarker(std::string_view line);

// A loader's error, re-reported at the view line that named the file; the message keeps the place
// in the loaded file: "contour file 'leaf.con' is broken: leaf.con:3: expected …".
[[noreturn]] void rethrowAtViewLine(const SourceLocation& where, const std::string& kind,
                                    std::string_view fileName, const DiagnosticError& inner);

}  // namespace hirsute
