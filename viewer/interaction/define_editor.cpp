#include "hirsute/viewer/interaction/define_editor.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "hirsute/core/output_target.h"

namespace hirsute {
namespace {

bool isNameStart(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

}  // namespace

std::vector<DefineConstant> findDefineConstants(const std::string& text) {
  std::vector<DefineConstant> constants;
  std::size_t lineStart = 0;
  int line = 1;
  while (lineStart <= text.size()) {
    std::size_t lineEnd = text.find('\n', lineStart);
    if (lineEnd == std::string::npos) lineEnd = text.size();
    std::size_t i = lineStart;
    auto skipBlanks = [&] {
      while (i < lineEnd && (text[i] == ' ' || text[i] == '\t')) ++i;
    };
    skipBlanks();
    if (i < lineEnd && text[i] == '#') {
      ++i;
      skipBlanks();
      if (text.compare(i, 6, "define") == 0 && i + 6 < lineEnd &&
          (text[i + 6] == ' ' || text[i + 6] == '\t')) {
        i += 6;
        skipBlanks();
        std::size_t nameStart = i;
        if (i < lineEnd && isNameStart(text[i])) {
          while (i < lineEnd && isNameChar(text[i])) ++i;
          std::string name = text.substr(nameStart, i - nameStart);
          // A '(' right after the name makes a function-like macro.
          if (i < lineEnd && text[i] != '(') {
            skipBlanks();
            std::size_t valueStart = i;
            while (i < lineEnd && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
            std::string value = text.substr(valueStart, i - valueStart);
            skipBlanks();
            bool restIsComment = i >= lineEnd || text.compare(i, 2, "//") == 0 ||
                                 text.compare(i, 2, "/*") == 0 || text[i] == '\r';
            char* end = nullptr;
            double number = value.empty() ? 0 : std::strtod(value.c_str(), &end);
            bool wholeNumber = !value.empty() && end == value.c_str() + value.size() &&
                               std::isfinite(number) &&
                               value.find_first_of("xXnNiI") == std::string::npos;
            if (restIsComment && wholeNumber) {
              DefineConstant c;
              c.name = name;
              c.text = value;
              c.value = number;
              c.integer = value.find_first_of(".eE") == std::string::npos;
              c.line = line;
              c.valueOffset = valueStart;
              c.valueLength = value.size();
              constants.push_back(c);
            }
          }
        }
      }
    }
    if (lineEnd == text.size()) break;
    lineStart = lineEnd + 1;
    ++line;
  }
  return constants;
}

std::string replaceDefineValues(const std::string& text,
                                const std::map<std::string, std::string>& values) {
  std::string out;
  std::size_t copied = 0;
  for (const DefineConstant& c : findDefineConstants(text)) {
    auto found = values.find(c.name);
    if (found == values.end()) continue;
    out.append(text, copied, c.valueOffset - copied);
    out += found->second;
    copied = c.valueOffset + c.valueLength;
  }
  out.append(text, copied, std::string::npos);
  return out;
}

std::string formatDefineValue(double value, bool integer) {
  if (integer) return std::to_string(static_cast<long long>(std::llround(value)));
  // The shortest text that reads back the same value.
  char buffer[64];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  *result.ptr = '\0';
  std::string s = buffer;
  // Keep it a floating-point literal, as it was.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

void saveDefineValues(const std::filesystem::path& file,
                      const std::map<std::string, std::string>& values) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the file");
  std::ostringstream text;
  text << in.rdbuf();
  in.close();
  std::string updated = replaceDefineValues(text.str(), values);
  OutputTarget out(file);
  std::FILE* stream = out.stream();
  if (std::fwrite(updated.data(), 1, updated.size(), stream) != updated.size())
    throw std::runtime_error(file.string() + ": cannot write the file");
  out.commit();
}

}  // namespace hirsute
