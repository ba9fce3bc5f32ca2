#include "hirsute/core/diagnostic.h"

#include <algorithm>

#include "hirsute/core/progress.h"
#include "hirsute/core/source_excerpt.h"

namespace hirsute {

namespace {

// The length of the well-formed UTF-8 sequence at `i` (RFC 3629: no overlong form, no
// surrogate, nothing past U+10FFFF), or 0 when the byte there starts none.
std::size_t utf8SequenceAt(const std::string& text, std::size_t i) {
  const auto byte = [&text](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xbf;  // the second byte's range
  if (c >= 0xc2 && c <= 0xdf) {
    length = 2;
  } else if (c >= 0xe0 && c <= 0xef) {
    length = 3;
    if (c == 0xe0) low = 0xa0;
    if (c == 0xed) high = 0x9f;
  } else if (c >= 0xf0 && c <= 0xf4) {
    length = 4;
    if (c == 0xf0) low = 0x90;
    if (c == 0xf4) high = 0x8f;
  } else {
    return 0;
  }
  if (i + length > text.size() || byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  return length;
}

}  // namespace

// A model's files may hold terminal control sequences (ESC, OSC) that a message quotes: they
// are shown as \xHH, never passed to the terminal, and the C1 controls' UTF-8 forms (C2 80 to
// C2 9F) as \u0080 to \u009f. A byte from 80 to 9F that is no part of a UTF-8 character is a
// C1 control itself to a terminal that reads 8-bit codes (9B is its CSI, 9D its OSC): it is
// shown as \xHH too. Newlines and tabs stay.
std::string printableText(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  static const char* const kHex = "0123456789abcdef";
  const auto escaped = [&out](const char* prefix, unsigned char c) {
    out += prefix;
    out += kHex[c >> 4];
    out += kHex[c & 15];
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      escaped("\\x", c);
    } else if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (const std::size_t length = utf8SequenceAt(text, i); length > 0) {
      if (c == 0xc2 && static_cast<unsigned char>(text[i + 1]) < 0xa0) {
        escaped("\\u00", static_cast<unsigned char>(text[i + 1]));
      } else {
        out.append(text, i, length);
      }
      i += length - 1;
    } else if (c < 0xa0) {
      escaped("\\x", c);
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string SourceLocation::text() const {
  std::string out = fileName();
  if (out.empty()) out = "<input>";
  if (line > 0) {
    out += ':' + std::to_string(line);
    if (column > 0) out += ':' + std::to_string(column);
  }
  return out;
}

std::string Diagnostic::text() const {
  std::string name;
  if (!warningName.empty())
    name = (severity == Severity::Error ? " [-Werror,-W" : " [-W") + warningName + "]";
  return printableText(where.text() + (severity == Severity::Error ? ": error: " : ": warning: ") +
                       message + name);
}

DiagnosticError::DiagnosticError(Diagnostic diagnostic)
    : std::runtime_error(diagnostic.text()), diagnostic_(std::move(diagnostic)) {}

DiagnosticError::DiagnosticError(const SourceLocation& where, const std::string& message)
    : DiagnosticError(Diagnostic{Severity::Error, where, message, {}}) {}

void Diagnostics::warn(const SourceLocation& where, const std::string& message,
                       const std::string& warningName) {
  if (!warningName.empty() &&
      std::find(silenced_.begin(), silenced_.end(), warningName) != silenced_.end()) {
    return;
  }
  for (const Diagnostic& seen : warnings_) {
    if (seen.message == message && seen.where.line == where.line &&
        seen.where.column == where.column && seen.where.fileName() == where.fileName()) {
      return;
    }
  }
  if (warnings_.size() >= kMaxPrinted) {
    ++suppressed_;
    return;
  }
  warnings_.push_back(
      Diagnostic{werror_ ? Severity::Error : Severity::Warning, where, message, warningName});
  if (echo_) {
    if (progress_) progress_->clear();
    *echo_ << report(warnings_.back());
  }
}

void Diagnostics::addSourceFolder(const ModelFolder& folder) {
  for (const ModelFolder& known : sourceFolders_)
    if (known.path() == folder.path()) return;
  sourceFolders_.push_back(folder);
}

std::string Diagnostics::report(const Diagnostic& diagnostic) const {
  for (const ModelFolder& folder : sourceFolders_) {
    const std::string excerpt = sourceExcerpt(diagnostic.where, folder);
    if (!excerpt.empty())
      return diagnostic.text() + "\n" + excerpt + macroNotes(diagnostic.where, diagnostic.message, folder);
  }
  return diagnostic.text() + "\n";
}

}  // namespace hirsute
