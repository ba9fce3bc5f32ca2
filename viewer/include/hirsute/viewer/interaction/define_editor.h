// The `#define` constants of a `.l` file as the viewer's panel shows them: found in the user's
// own text (not the preprocessed one), changed, and written back with the rest of the file
// untouched, so that `hirsute view --save` keeps the modeller's layout and comments.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace hirsute {

// `#define NAME VALUE` where VALUE is one number (`5`, `-0.25`, `1e3`), possibly followed by a
// comment. Function-like macros and other values are left alone: they are not knobs.
struct DefineConstant {
  std::string name;
  std::string text;  // the value as written
  double value = 0;
  bool integer = false;                          // written without a point or exponent
  int line = 0;                                  // 1-based
  std::size_t valueOffset = 0, valueLength = 0;  // of `text` in the file's text
};

std::vector<DefineConstant> findDefineConstants(const std::string& text);

// The text with each named constant's value replaced (names not found are ignored).
std::string replaceDefineValues(const std::string& text,
                                const std::map<std::string, std::string>& values);

// A value as the panel writes it: integers as integers, others in the shortest form that reads
// back the same.
std::string formatDefineValue(double value, bool integer);

// Reads `file`, replaces the values and writes it back (under a temporary name, renamed over
// it). Throws std::runtime_error when it cannot.
void saveDefineValues(const std::filesystem::path& file,
                      const std::map<std::string, std::string>& values);

}  // namespace hirsute
