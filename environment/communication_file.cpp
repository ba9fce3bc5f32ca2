#include "hirsute/environment/communication_file.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "hirsute/core/characters.h"
#include "hirsute/environment/keyword_file.h"
#include "hirsute/lsys/printf_format.h"

namespace hirsute {
namespace {

constexpr std::size_t kMaxLine = 4095;

// Checks that printf can apply `format` to `values` doubles: every conversion a floating one
// (flags, width and precision as digits, an optional `l`), at most `values` of them. Returns the
// number of conversions and sets `first` to the offset of the first one.
int checkFormat(const KeywordLine& line, const std::string& format, int values,
                std::size_t& first) {
  const int base = static_cast<int>(line.rest) + 1;
  int conversions = 0;
  first = 0;
  for (std::size_t i = 0; i < format.size(); ++i) {
    if (format[i] != '%') continue;
    if (i + 1 < format.size() && format[i + 1] == '%') {
      ++i;
      continue;
    }
    const std::size_t start = i;
    std::size_t j = i + 1;
    while (j < format.size() && isOneOf(format[j], "-+ #0'")) ++j;
    // The field width and the precision: each at most kMaxPrintfField characters, as in a
    // block's printf (a width of 2·10⁹ would ask printf for gigabytes a query).
    const auto field = [&](const char* what) {
      const std::size_t digits = j;
      long long value = 0;
      while (j < format.size() && std::isdigit(static_cast<unsigned char>(format[j]))) {
        value = std::min<long long>(value * 10 + (format[j] - '0'), 1LL << 40);
        ++j;
      }
      if (value > kMaxPrintfField) {
        throw DiagnosticError(line.at(base + static_cast<int>(digits)),
                              "the format asks for a " + std::string(what) + " of " +
                                  std::string(format, digits, j - digits) +
                                  " characters; the limit is " + std::to_string(kMaxPrintfField));
      }
    };
    field("field width");
    if (j < format.size() && format[j] == '.') {
      ++j;
      field("precision");
    }
    if (j < format.size() && format[j] == 'l') ++j;
    if (j >= format.size() || !isOneOf(format[j], "fFeEgGaA")) {
      throw DiagnosticError(line.at(base + static_cast<int>(start)),
                            "the format's conversion must be one for a floating value (%f, %e, "
                            "%g or %a, with flags, width and precision)");
    }
    if (conversions == 0) first = start;
    if (++conversions > values) {
      throw DiagnosticError(line.at(base + static_cast<int>(start)),
                            "the format has more conversions than the " + std::to_string(values) +
                                (values == 1 ? " value" : " values") + " it formats");
    }
    i = j;
  }
  return conversions;
}

// The first word of the rest of the line (words separated by blanks, TABs and `:`).
std::vector<KeywordToken> words(const KeywordLine& line) {
  return line.tokens(" \t:");
}

bool firstWordIs(const KeywordLine& line, const char* word) {
  std::vector<KeywordToken> w = words(line);
  return !w.empty() && w.front().text == word;
}

void readInterpretedModules(const KeywordLine& line, CommunicationFile& out) {
  for (const KeywordToken& t : line.tokens(",; \t")) {
    if (t.text == "all") {
      out.interpretAll = true;
    } else if (t.text.size() == 1) {
      out.interpreted.push_back(InterpretedModule{t.text[0], -1});
    } else if (t.text.size() == 4 && t.text[1] == '(' && t.text[3] == ')' && t.text[2] >= '0' &&
               t.text[2] <= '6') {
      out.interpreted.push_back(InterpretedModule{t.text[0], t.text[2] - '0'});
    } else {
      throw DiagnosticError(line.at(t.column),
                            "expected 'all', a module symbol or a module with "
                            "its parameter count such as F(2), found '" +
                                t.text + "'");
    }
  }
}

CommunicationFile communicationFileOf(const std::vector<KeywordLine>& lines,
                                      const std::filesystem::path& file, Diagnostics& diagnostics) {
  CommunicationFile out;
  out.file = file;
  static const char* const kTurtleKeywords[kTurtleValues] = {
      "turtle position", "turtle heading",    "turtle left",
      "turtle up",       "turtle line width", "turtle scale factor"};
  for (const KeywordLine& line : lines) {
    const std::string& k = line.keyword;
    bool known = true;
    if (k == "executable") {
      out.executable = line.restText();
      out.executableWhere = line.at(static_cast<int>(line.rest) + 1);
    } else if (k == "communication type") {
      std::vector<KeywordToken> w = words(line);
      const std::string type = w.empty() ? std::string() : w[0].text;
      if (type == "files") {
        out.transport = Transport::Files;
      } else if (type == "memory") {
        out.transport = Transport::Memory;
      } else if (type == "pipes") {
        out.transport = Transport::Pipes;
      } else if (type == "sockets") {
        out.transport = Transport::Sockets;
      } else {
        diagnostics.warn(line.at(w.empty() ? static_cast<int>(line.rest) + 1 : w[0].column),
                         "unknown communication type '" + type + "'; pipes are used");
        out.transport = Transport::Pipes;
      }
      out.chunkLimit = out.transport == Transport::Files ? 1000 : 100;
      if (w.size() > 1) {
        const int limit = std::atoi(w[1].text.c_str());
        if (limit > 0) {
          out.chunkLimit = limit;
        }
      }
    } else if (k == "following module") {
      std::vector<KeywordToken> w = words(line);
      if (w.empty() || (w[0].text != "yes" && w[0].text != "no")) {
        throw DiagnosticError(line.at(w.empty() ? static_cast<int>(line.rest) + 1 : w[0].column),
                              "expected 'yes' or 'no'");
      }
      out.followingModule = w[0].text == "yes";
    } else if (k == "interpreted modules") {
      readInterpretedModules(line, out);
    } else if (k == "when interpret") {
      for (const KeywordToken& t : line.tokens(",; \t")) {
        const int n = keywordInteger(line, t);
        if (n > 6)
          throw DiagnosticError(line.at(t.column), "a module has at most 6 parameters here");
        out.whenInterpret.push_back(n);
      }
    } else if (k == "verbose") {
      out.verbose = firstWordIs(line, "on");
    } else if (k == "strings only" || k == "binary data") {
      if (firstWordIs(line, "on")) {
        throw DiagnosticError(line.at(1),
                              "'" + k + "' exchanges are not supported; only ?E records are");
      }
    } else if (k == "remote host") {
      out.remoteHost = line.restText();
    } else {
      known = false;
      for (int v = 0; v < kTurtleValues; ++v) {
        if (k != kTurtleKeywords[v]) continue;
        TurtleFormat& f = out.turtle[static_cast<std::size_t>(v)];
        f.present = true;
        f.format = line.restText();
        f.conversions = checkFormat(line, f.format, v < kLineWidth ? 3 : 1, f.firstConversion);
        known = true;
      }
    }
    if (!known) warnUnknownKeyword(line, diagnostics, "communication file");
  }
  if (!out.interpreted.empty() || out.interpretAll || !out.whenInterpret.empty()) {
    diagnostics.warn(SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0},
                     "graphics requests (interpreted modules, when interpret) are not sent: the "
                     "environment gets the queries without the modules' geometry");
  }
  return out;
}

}  // namespace

CommunicationFile readCommunicationFile(const std::filesystem::path& file,
                                        Diagnostics& diagnostics) {
  return communicationFileOf(readKeywordLines(file, kMaxLine), file, diagnostics);
}

CommunicationFile parseCommunicationFile(std::string_view text, const std::filesystem::path& file,
                                         Diagnostics& diagnostics) {
  return communicationFileOf(keywordLines(text, file, kMaxLine), file, diagnostics);
}

}  // namespace hirsute
