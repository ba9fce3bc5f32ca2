// Reading a line of the view file (view_file.cpp), for the view file's own lines and for the
// lines each organ adds (docs/design.md, "Organs"): an organ lists its lines as
// ViewLineCommand in a file of its own in its folder (hairs/plant/hair_view_lines.cpp and the
// others) and organViewLines() (hairs/organs/organ_models.cpp) gathers them, so that the view file
// names no organ.
#pragma once

#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include <glm/glm.hpp>

#include "hirsute/core/diagnostic.h"
#include "hirsute/core/model_folder.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/lsys/view_file_lines.h"

namespace hirsute {

// The view file's reading of text, as cpfg's sscanf reads it.
namespace view_text {
std::string inQuotes(std::string_view text);
bool isBlank(char c);
// A number at the front of `text` as sscanf's %f reads it: an optional sign, digits, a fraction,
// an exponent. Returns the value and the characters used; nothing when no number starts there.
// Infinite and NaN values are refused: no view setting means them.
std::optional<std::pair<double, std::size_t>> numberAtFront(std::string_view text);
// An integer at the front of `text`, as %d reads it.
std::optional<std::pair<long, std::size_t>> integerAtFront(std::string_view text);
// A whole word as a number; used where words are separated first (light, texture, tropism).
std::optional<double> wholeNumber(std::string_view word);
}  // namespace view_text

// The arguments of one command, read front to back as sscanf reads them.
class ViewArguments {
 public:
  explicit ViewArguments(const ViewFileLine& line) : line_(line), text_(line.rest) {}

  void skipBlanks() {
    while (position_ < text_.size() && view_text::isBlank(text_[position_])) ++position_;
  }
  bool atEnd() {
    skipBlanks();
    return position_ >= text_.size();
  }
  // Where the next argument starts (after blanks).
  SourceLocation here() {
    skipBlanks();
    return line_.at(position_);
  }
  // The next blank-separated word, without consuming it ("" at the end).
  std::string_view peekWord() {
    skipBlanks();
    std::size_t end = position_;
    while (end < text_.size() && !view_text::isBlank(text_[end])) ++end;
    return text_.substr(position_, end - position_);
  }
  std::optional<std::string_view> word() {
    const std::string_view next = peekWord();
    if (next.empty()) return std::nullopt;
    position_ += next.size();
    return next;
  }
  std::optional<double> number() {
    skipBlanks();
    const auto number = view_text::numberAtFront(text_.substr(position_));
    if (!number) return std::nullopt;
    position_ += number->second;
    return number->first;
  }
  std::optional<long> integer() {
    skipBlanks();
    const auto number = view_text::integerAtFront(text_.substr(position_));
    if (!number) return std::nullopt;
    position_ += number->second;
    return number->first;
  }
  // A literal such as ',' or "x:"; blanks before it are allowed (sscanf would not skip them
  // before a comma; accepting `0 , 1` costs nothing).
  bool literal(std::string_view expected) {
    skipBlanks();
    if (text_.substr(position_, expected.size()) != expected) return false;
    position_ += expected.size();
    return true;
  }
  void skipAll() { position_ = text_.size(); }
  std::string_view remaining() {
    skipBlanks();
    std::string_view rest = text_.substr(position_);
    while (!rest.empty() && view_text::isBlank(rest.back())) rest.remove_suffix(1);
    return rest;
  }

 private:
  const ViewFileLine& line_;
  std::string_view text_;
  std::size_t position_ = 0;
};

// One view-file line being read: its arguments, the settings it changes, and how it reports.
class ViewLine {
 public:
  ViewLine(const ViewFileLine& line, ViewSettings& view, Diagnostics& diagnostics,
           const std::filesystem::path& folder)
      : args(line), view(view), line_(line), diagnostics_(diagnostics), folder_(folder) {}

  const ViewFileLine& line() const { return line_; }
  std::string_view label() const { return line_.label; }
  // Where the label starts: messages about the whole line point there.
  SourceLocation labelAt() const {
    SourceLocation where = line_.where;
    where.column = line_.restColumn - static_cast<int>(line_.label.size());
    return where;
  }

  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    throw DiagnosticError(where, message);
  }
  void warn(const SourceLocation& where, const std::string& message) {
    diagnostics_.warn(where, message);
  }

  // A setting that cannot be read: a warning, and the setting keeps its value (cpfg).
  void ignoreLine(const SourceLocation& where, const std::string& expected) {
    const std::string found = std::string(args.peekWord());
    warn(where, "expected " + expected + " after " + view_text::inQuotes(label()) + ", found " +
                    (found.empty() ? std::string("nothing") : view_text::inQuotes(found)) +
                    "; the line is ignored");
    args.skipAll();
    ignored_ = true;
  }
  bool ignored() const { return ignored_; }

  // Settings: nothing is returned (and a warning given) when the value cannot be read.
  std::optional<double> settingNumber() {
    const SourceLocation where = args.here();
    const std::optional<double> value = args.number();
    if (!value) ignoreLine(where, "a number");
    return value;
  }
  std::optional<int> settingInteger() {
    const SourceLocation where = args.here();
    const std::optional<long> value = args.integer();
    if (!value || *value < std::numeric_limits<int>::min() ||
        *value > std::numeric_limits<int>::max()) {
      ignoreLine(where, "an integer");
      return std::nullopt;
    }
    return static_cast<int>(*value);
  }
  // `x,y,z`.
  std::optional<glm::vec3> settingTriple() {
    glm::vec3 out;
    for (int k = 0; k < 3; ++k) {
      const SourceLocation where = args.here();
      if (k > 0 && !args.literal(",")) {
        ignoreLine(where, "three numbers separated by commas (x,y,z)");
        return std::nullopt;
      }
      const SourceLocation numberAt = args.here();
      const std::optional<double> value = args.number();
      if (!value) {
        ignoreLine(numberAt, "three numbers separated by commas (x,y,z)");
        return std::nullopt;
      }
      out[k] = static_cast<float>(*value);
    }
    return out;
  }
  // One of `words`; the index of the word found.
  std::optional<std::size_t> settingWord(std::initializer_list<std::string_view> words,
                                         const std::string& expected) {
    const SourceLocation where = args.here();
    const std::string_view word = args.peekWord();
    std::size_t index = 0;
    for (std::string_view candidate : words) {
      if (word == candidate) {
        args.word();
        return index;
      }
      ++index;
    }
    ignoreLine(where, expected);
    return std::nullopt;
  }
  std::optional<bool> settingFlag() {
    const std::optional<std::size_t> word = settingWord({"on", "off"}, "on or off");
    if (!word) return std::nullopt;
    return *word == 0;
  }

  // Declarations: an error when the value cannot be read.
  std::string_view requiredWord(const std::string& what) {
    const SourceLocation where = args.here();
    const std::optional<std::string_view> word = args.word();
    if (!word) fail(where, "expected " + what + " after " + view_text::inQuotes(label()));
    return *word;
  }
  long requiredInteger(const std::string& what, long min, long max) {
    const SourceLocation where = args.here();
    const std::string_view word = args.peekWord();
    const auto number = view_text::integerAtFront(word);
    if (!number || number->second != word.size()) {
      fail(where, "expected " + what + " after " + view_text::inQuotes(label()) + ", found " +
                      (word.empty() ? std::string("nothing") : view_text::inQuotes(word)));
    }
    if (number->first < min || number->first > max) {
      fail(where, what + " must be from " + std::to_string(min) + " to " + std::to_string(max) +
                      ", found " + std::to_string(number->first));
    }
    args.word();
    return number->first;
  }
  double requiredNumber(const std::string& what) {
    const SourceLocation where = args.here();
    const std::string_view word = args.peekWord();
    const std::optional<double> value = view_text::wholeNumber(word);
    if (!value) {
      fail(where, "expected " + what + " after " + view_text::inQuotes(label()) + ", found " +
                      (word.empty() ? std::string("nothing") : view_text::inQuotes(word)));
    }
    args.word();
    return *value;
  }

  // Text left after the arguments: cpfg's sscanf ignores it; Hirsute says so.
  void finish() {
    if (ignored_) return;
    const SourceLocation where = args.here();
    const std::string_view rest = args.remaining();
    if (!rest.empty()) {
      warn(where, view_text::inQuotes(rest) + " after the arguments of " +
                      view_text::inQuotes(label()) + " is ignored");
    }
  }

  // A file name of the view file, resolved against its folder. The name must stay beneath that
  // folder (model_folder.h): an absolute name, a `..`, a link out of the folder, a FIFO or a
  // device is an error here, at the reference; a missing file is for its reader to report.
  std::string resolve(std::string_view name, const SourceLocation& where) const {
    const ModelFolder folder(folder_);
    const std::string refused = folder.refusal(std::string(name));
    if (!refused.empty()) fail(where, "cannot open " + view_text::inQuotes(name) + ": " + refused);
    return folder.pathOf(std::string(name)).string();
  }

  // The view file's folder, against which its file names are resolved.
  const std::filesystem::path& folder() const { return folder_; }

  ViewArguments args;
  ViewSettings& view;

 private:
  const ViewFileLine& line_;
  Diagnostics& diagnostics_;
  const std::filesystem::path& folder_;
  bool ignored_ = false;
};

using ViewLineReader = void (*)(ViewLine&);

// A line an organ adds to the view file: its label, spelled as users write it ("hair texture:"),
// and what reads it.
struct ViewLineCommand {
  std::string_view label;
  ViewLineReader read;
};

// Every organ's lines, in the order of the organs' module tables (hairs/organs/organ_list.h),
// defined at link time by the registry.
std::span<const std::span<const ViewLineCommand>> organViewLines();

}  // namespace hirsute
