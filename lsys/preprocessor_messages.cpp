#include "hirsute/lsys/preprocessor_messages.h"

#include <memory>
#include <sstream>
#include <string>

#include "hirsute/core/model_folder.h"

namespace hirsute {
namespace {

// A file name cpp names (a `#line` may set any) longer than a path can be is shortened too.
constexpr std::size_t kMaxFileNameBytes = 4096;

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

// The digits starting at `at`: their end, or `at` when there are none.
std::size_t digitsEnd(std::string_view line, std::size_t at) {
  while (at < line.size() && isDigit(line[at])) ++at;
  return at;
}

// A line number or column as cpp printed it; absurd values (a `#line` beyond int) read as 0.
int cppNumber(std::string_view digits) {
  if (digits.empty() || digits.size() > 9) return 0;
  int value = 0;
  for (char c : digits) value = value * 10 + (c - '0');
  return value;
}

// ` *(fatal error|error|warning): ` at `at`: where the text after it starts, or npos.
std::size_t afterKind(std::string_view line, std::size_t at, bool& warning) {
  while (at < line.size() && line[at] == ' ') ++at;
  const std::string_view rest = line.substr(at);
  for (std::string_view kind : {"fatal error: ", "error: ", "warning: "}) {
    if (rest.substr(0, kind.size()) == kind) {
      warning = kind[0] == 'w';
      return at + kind.size();
    }
  }
  return std::string_view::npos;
}

bool endsWith(const std::string& text, const std::string& end) {
  return text.size() > end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

// Traditional-mode cpp reports an `#include` file it cannot read one line late, at the word
// `include`.
// Moves `where` to the file name on the directive's own line, as the user would look for it.
// The file is read beneath the model's folder (a `#line` may name any file).
void locateMissingInclude(SourceLocation& where, const std::string& header,
                          const std::filesystem::path& folder) {
  const ModelFolder model(folder.empty() ? std::filesystem::path(".") : folder);
  const std::filesystem::path file(where.fileName());
  std::string source, failure;
  const std::string relative = file.is_absolute() == model.path().is_absolute()
                                   ? file.lexically_relative(model.path()).string()
                                   : std::string();
  if (relative.empty() || !model.read(relative, source, failure, std::size_t{64} << 20)) return;
  std::istringstream in(source);
  std::string text;
  for (int number = 1; std::getline(in, text) && number <= where.line; ++number) {
    if (number < where.line - 1) continue;
    std::size_t directive = text.find('#');
    std::size_t include = text.find("include", directive == std::string::npos ? 0 : directive);
    if (directive == std::string::npos || include == std::string::npos) continue;
    std::size_t name = text.find(header, include);
    // cpp names a file found through -I by its path there; the line has the name as written.
    if (name == std::string::npos) {
      const std::string written = std::filesystem::path(header).filename().string();
      name = written.empty() ? std::string::npos : text.find(written, include);
      if (name != std::string::npos) name = text.find_last_of("\"<", name);
      if (name != std::string::npos) ++name;
    }
    if (name == std::string::npos || name == 0) continue;
    where.line = number;
    where.column = static_cast<int>(name);  // the opening quote or angle bracket, 1-based
    return;
  }
}

}  // namespace

bool parsePreprocessorMessage(std::string_view line, PreprocessorMessage& message) {
  // The shortest file name that works, as cpp's own file names may hold colons: each colon is
  // tried once, with a column and without, so a line costs time in proportion to its length.
  for (std::size_t colon = line.find(':'); colon != std::string_view::npos;
       colon = line.find(':', colon + 1)) {
    const std::size_t lineEnd = digitsEnd(line, colon + 1);
    if (lineEnd == colon + 1 || lineEnd >= line.size() || line[lineEnd] != ':') continue;
    bool warning = false;
    std::size_t columnEnd = digitsEnd(line, lineEnd + 1);
    std::size_t text = std::string_view::npos;
    if (columnEnd > lineEnd + 1 && columnEnd < line.size() && line[columnEnd] == ':') {
      text = afterKind(line, columnEnd + 1, warning);
    }
    if (text == std::string_view::npos) {
      columnEnd = lineEnd;  // no column
      text = afterKind(line, lineEnd + 1, warning);
    }
    if (text == std::string_view::npos) continue;
    message.file = std::string(line.substr(0, colon));
    message.line = cppNumber(line.substr(colon + 1, lineEnd - colon - 1));
    message.column =
        columnEnd > lineEnd ? cppNumber(line.substr(lineEnd + 1, columnEnd - lineEnd - 1)) : 0;
    message.warning = warning;
    message.text = std::string(line.substr(text));
    return true;
  }
  return false;
}

std::string shortenedMessage(std::string_view text, std::size_t maxBytes) {
  if (text.size() <= maxBytes) return std::string(text);
  const auto continuation = [&](std::size_t at) {
    return at < text.size() && (static_cast<unsigned char>(text[at]) & 0xc0) == 0x80;
  };
  std::size_t head = maxBytes * 2 / 3;
  std::size_t tail = text.size() - (maxBytes - head);
  while (head > 0 && continuation(head)) --head;
  while (continuation(tail)) ++tail;
  return std::string(text.substr(0, head)) + " … (" + std::to_string(tail - head) +
         " bytes left out) … " + std::string(text.substr(tail));
}

void reportPreprocessorMessages(const std::string& messages, const std::string& failure,
                                const std::string& fallbackFile,
                                const std::filesystem::path& folder, Diagnostics& diagnostics) {
  std::istringstream lines(messages);
  std::string line;
  PreprocessorMessage parsed;
  while (std::getline(lines, line)) {
    if (!parsePreprocessorMessage(line, parsed)) continue;
    SourceLocation where{
        std::make_shared<const std::string>(shortenedMessage(parsed.file, kMaxFileNameBytes)),
        parsed.line, parsed.column};
    const std::string shown = shortenedMessage(parsed.text, kMaxPreprocessorMessageBytes);
    if (parsed.warning) {
      diagnostics.warn(where, shown);
      continue;
    }
    // cpp's reasons for not reading an #include file: the message is "NAME: REASON".
    for (const char* reason :
         {": No such file or directory", ": File name too long", ": Is a directory",
          ": Not a directory", ": Too many levels of symbolic links"}) {
      if (endsWith(parsed.text, reason)) {
        const std::size_t length = std::char_traits<char>::length(reason);
        locateMissingInclude(where, parsed.text.substr(0, parsed.text.size() - length), folder);
        break;
      }
    }
    // The confinement's refusal (child_confinement.h) reads as a denied permission.
    static const std::string kDenied = ": Permission denied";
    if (endsWith(parsed.text, kDenied)) {
      locateMissingInclude(where, parsed.text.substr(0, parsed.text.size() - kDenied.size()),
                           folder);
      throw DiagnosticError(where, shown +
                                       " (an #include reads only files beneath the model's "
                                       "folder; no link out of it is followed)");
    }
    throw DiagnosticError(where, shown);
  }
  if (!failure.empty()) {
    std::string said = messages;
    while (!said.empty() && (said.back() == '\n' || said.back() == ' ')) said.pop_back();
    throw DiagnosticError(
        SourceLocation{std::make_shared<const std::string>(fallbackFile), 0, 0},
        "the C preprocessor failed (" + failure + ")" +
            (said.empty() ? std::string(" without a message")
                          : ": " + shortenedMessage(said, kMaxPreprocessorMessageBytes)));
  }
}

}  // namespace hirsute
