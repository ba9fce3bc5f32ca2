#include "hirsute/lsys/diagnostic.h"

#include "hirsute/lsys/progress.h"

namespace hirsute {

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
  return where.text() + (severity == Severity::Error ? ": error: " : ": warning: ") + message;
}

DiagnosticError::DiagnosticError(Diagnostic diagnostic)
    : std::runtime_error(diagnostic.text()), diagnostic_(std::move(diagnostic)) {}

DiagnosticError::DiagnosticError(const SourceLocation& where, const std::string& message)
    : DiagnosticError(Diagnostic{Severity::Error, where, message}) {}

void Diagnostics::warn(const SourceLocation& where, const std::string& message) {
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
  warnings_.push_back(Diagnostic{Severity::Warning, where, message});
  if (echo_) {
    if (progress_) progress_->clear();
    *echo_ << warnings_.back().text() << '\n';
  }
}

}  // namespace hirsute
