#include "hirsute/core/source_excerpt.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

namespace hirsute {
namespace {

constexpr std::size_t kMaxScannedBytes = std::size_t{64} << 20;  // a line deeper is not shown
constexpr std::size_t kShownAround = 60;  // bytes of a long line shown each side of the column

// The name relative to the folder, as ModelFolder takes it: a location names its file as the
// user finds it, the folder joined with the name (ModelFolder::pathOf).
std::string nameInFolder(const std::string& shown, const ModelFolder& folder) {
  const std::string prefix = folder.path().string();
  if (prefix == "." || prefix.empty()) return shown;
  const std::string joined = prefix.back() == '/' ? prefix : prefix + "/";
  if (shown.compare(0, joined.size(), joined) == 0) return shown.substr(joined.size());
  return shown;  // absolute or elsewhere: ModelFolder refuses it
}

// Line `number` (1-based) of the open file, without its newline; false when the file is shorter.
bool readLine(int fd, int number, std::string& line) {
  std::string buffer(1 << 16, '\0');
  std::size_t scanned = 0;
  int current = 1;
  line.clear();
  for (;;) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got <= 0) return current == number && !line.empty();
    scanned += static_cast<std::size_t>(got);
    for (ssize_t i = 0; i < got; ++i) {
      const char c = buffer[static_cast<std::size_t>(i)];
      if (c == '\n') {
        if (current == number) return true;
        ++current;
      } else if (current == number) {
        line += c;
        if (line.size() > kMaxScannedBytes) return true;
      }
    }
    if (scanned > kMaxScannedBytes && current < number) return false;
  }
}

}  // namespace

std::string sourceExcerpt(const SourceLocation& where, const ModelFolder& folder) {
  if (where.line <= 0 || !where.file || where.file->empty()) return {};
  ConfinedFile file = folder.open(nameInFolder(*where.file, folder), FileAccess::Read);
  if (!file) return {};
  std::string line;
  if (!readLine(file.fd.get(), where.line, line)) return {};
  if (!line.empty() && line.back() == '\r') line.pop_back();

  // The column is a byte's (1-based); past the end it points just after the line.
  std::size_t caret = where.column > 0 ? static_cast<std::size_t>(where.column - 1) : 0;
  caret = std::min(caret, line.size());
  std::string lead;
  if (line.size() > 2 * kShownAround + 20) {
    const std::size_t from = caret > kShownAround ? caret - kShownAround : 0;
    const std::size_t to = std::min(line.size(), caret + kShownAround);
    line = (from > 0 ? "..." : "") + line.substr(from, to - from) + (to < line.size() ? "..." : "");
    caret = caret - from + (from > 0 ? 3 : 0);
  }
  // A control byte shows as \xHH: the part before the caret is shown on its own, so that the
  // caret stays under the character it points at.
  const std::string shownBefore = printableText(line.substr(0, caret));
  line = shownBefore + printableText(line.substr(caret));
  caret = shownBefore.size();

  std::string pad;
  for (std::size_t i = 0; i < caret && i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    if ((c & 0xc0) == 0x80) continue;  // a UTF-8 continuation byte: the character has its space
    pad += c == '\t' ? '\t' : ' ';
  }
  const std::string number = std::to_string(where.line);
  const std::string gutter(number.size(), ' ');
  return " " + number + " | " + line + "\n " + gutter + " | " + pad + "^\n";
}

}  // namespace hirsute
