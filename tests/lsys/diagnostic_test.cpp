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

// A byte from 80 to 9F outside a UTF-8 character is a C1 control to an 8-bit terminal (9B CSI,
// 9D OSC); the same byte inside one (ś is C5 9B, × is C3 97) is text.
TEST(DiagnosticText, RawC1BytesAreShownAndUtf8CharactersStay) {
  EXPECT_EQ(printableText("found '\x9b"
                          "31mred\x9d"
                          "0;t\x07'"),
            "found '\\x9b31mred\\x9d0;t\\x07'");
  EXPECT_EQ(printableText("\xc5\x9b \xc3\x97 \xe2\x80\x94"), "\xc5\x9b \xc3\x97 \xe2\x80\x94");
  // A lead byte without its continuation, and an overlong form of CSI (C0 9B, E0 82 9B).
  EXPECT_EQ(printableText("\xc5 \x9b|\xc0\x9b|\xe0\x82\x9b"),
            "\xc5 \\x9b|\xc0\\x9b|\xe0\\x82\\x9b");
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
