// Diagnostics as they are printed: terminal control bytes a model's file holds are shown, never
// passed to the terminal.
#include "hirsute/core/diagnostic.h"

#include <sstream>

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace hirsute {
namespace {

TEST(DiagnosticText, ControlBytesAreShownNotPassedOn) {
  const SourceLocation where{std::make_shared<const std::string>("a\x1b[2Jb.v"), 3, 1};
  const Diagnostic d{Severity::Warning, where,
                     "unknown command '\x1b]0;title\x07:'\tnext\x7f \xc2\x9b"
                     "31m",
                     {}};
  const std::string text = d.text();
  EXPECT_EQ(text,
            "a\\x1b[2Jb.v:3:1: warning: unknown command '\\x1b]0;title\\x07:'\tnext\\x7f "
            "\\u009b31m");
  for (char c : text) EXPECT_FALSE(c == '\x1b' || c == '\x07' || c == '\x7f');
}

TEST(DiagnosticText, PrintableTextAndUtf8StayAsTheyAre) {
  const Diagnostic d{Severity::Error,
                     SourceLocation{std::make_shared<const std::string>("m.l"), 1, 2},
                     "\xc3\xa9t\xc3\xa9 \xc2\xb0"
                     "C\nsecond line",
                     {}};
  EXPECT_EQ(d.text(),
            "m.l:1:2: error: \xc3\xa9t\xc3\xa9 \xc2\xb0"
            "C\nsecond line");
}

TEST(Diagnostics, NamedWarningIsSilencedOrMadeAnError) {
  const SourceLocation where{std::make_shared<const std::string>("m.l"), 4, 7};
  std::ostringstream out;
  Diagnostics diagnostics(&out);
  diagnostics.silence("unused-production");
  diagnostics.warn(where, "silenced", "unused-production");
  diagnostics.warn(where, "said", "parameter-count");
  EXPECT_EQ(out.str(), "m.l:4:7: warning: said [-Wparameter-count]\n");
  EXPECT_FALSE(diagnostics.failed());

  std::ostringstream strict;
  Diagnostics werror(&strict);
  werror.setWerror(true);
  EXPECT_FALSE(werror.failed());
  werror.warn(where, "said", "parameter-count");
  EXPECT_EQ(strict.str(), "m.l:4:7: error: said [-Werror,-Wparameter-count]\n");
  EXPECT_TRUE(werror.failed());
}

}  // namespace
}  // namespace hirsute
