#include "hirsute/core/diagnostic.h"

#include <algorithm>

#include "hirsute/core/progress.h"

namespace hirsute {

// A model's files may hold terminal control sequences (ESC, OSC) that a message quotes: they
// are shown as \xHH, never passed to the terminal, and the C1 controls' UTF-8 forms (C2 80 to
// C2 9F) as \u0080 to \u009f. Newlines and tabs stay.
std::string printableText(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  static const char* const kHex = "0123456789abcdef";
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else if (c == 0xc2 && i + 1 < text.size() &&
               (static_cast<unsigned char>(text[i + 1]) & 0xe0) == 0x80) {
      const auto next = static_cast<unsigned char>(text[++i]);
      out += "\\u00";
      out += kHex[next >> 4];
      out += kHex[next & 15];
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
    *echo_ << warnings_.back().text() << '\n';
  }
}

}  // namespace hirsute
