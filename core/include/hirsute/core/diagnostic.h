// Diagnostics: the one error mechanism of Hirsute. Every stage reports problems as a Diagnostic
// with a location in the user's own file; errors are thrown as DiagnosticError and printed by the
// command line as `file:line:col: error: message`.
#pragma once

#include <cstddef>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hirsute/core/model_folder.h"

namespace hirsute {

class Progress;

struct SourceLocation {
  std::shared_ptr<const std::string> file;  // shared: every location of one file points to one name
  int line = 0;                              // 1-based; 0 when unknown
  int column = 0;                            // 1-based; 0 when unknown

  std::string fileName() const { return file ? *file : std::string(); }
  // "file:line:col", "file:line" or "file", as much as is known.
  std::string text() const;
};

// `text` with its terminal control bytes shown as \xHH and the C1 controls' UTF-8 forms as
// \u00HH, for a message that quotes a model's file (newlines and tabs stay).
std::string printableText(const std::string& text);

enum class Severity { Warning, Error };

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceLocation where;
  std::string message;
  // The name of a warning that `-W no-NAME` silences; empty for the others.
  std::string warningName;

  // "file:line:col: error: message", and " [-WNAME]" after a named warning (" [-Werror,-WNAME]"
  // when --Werror made it an error), as clang writes them.
  std::string text() const;
};

// Thrown for every error that ends a run; the command line prints it and exits with code 2.
class DiagnosticError : public std::runtime_error {
 public:
  explicit DiagnosticError(Diagnostic diagnostic);
  DiagnosticError(const SourceLocation& where, const std::string& message);
  const Diagnostic& diagnostic() const { return diagnostic_; }

 private:
  Diagnostic diagnostic_;
};

// Collects warnings; prints each as it arrives when given a stream. A warning repeated at the same
// location is printed once, and after kMaxPrinted distinct warnings the rest are only counted.
// A named warning that was silenced is dropped; with werror set, every warning is kept as an
// error, and the command ends with exit code 2 once the stage that gave it is done (failed()).
class Diagnostics {
 public:
  static constexpr std::size_t kMaxPrinted = 50;

  explicit Diagnostics(std::ostream* echo = nullptr) : echo_(echo) {}

  void warn(const SourceLocation& where, const std::string& message,
            const std::string& warningName = {});
  void silence(const std::string& warningName) { silenced_.push_back(warningName); }
  void setWerror(bool werror) { werror_ = werror; }
  // Some warning was made an error by werror.
  bool failed() const { return werror_ && (!warnings_.empty() || suppressed_ > 0); }
  const std::vector<Diagnostic>& warnings() const { return warnings_; }
  std::size_t suppressed() const { return suppressed_; }
  void setEcho(std::ostream* echo) { echo_ = echo; }
  // The progress line on the same terminal, cleared before a warning is printed.
  void setProgress(Progress* progress) { progress_ = progress; }
  // A folder whose files the messages quote: each printed diagnostic shows the line it points
  // at with a caret (source_excerpt.h), when its file lies beneath one of these folders.
  void addSourceFolder(const ModelFolder& folder);
  // What a command prints for a diagnostic: its text, then the line it points at and a caret.
  // Ends in a newline.
  std::string report(const Diagnostic& diagnostic) const;

 private:
  std::ostream* echo_;
  Progress* progress_ = nullptr;
  std::vector<ModelFolder> sourceFolders_;
  std::vector<Diagnostic> warnings_;
  std::size_t suppressed_ = 0;
  std::vector<std::string> silenced_;
  bool werror_ = false;
};

}  // namespace hirsute
