#include "hirsute/core/edited_text.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "hirsute/core/output_folder.h"
#include "hirsute/core/output_target.h"

namespace hirsute {

EditedText EditedText::split(std::string_view text) {
  EditedText edited;
  edited.finalNewline = text.empty() || text.back() == '\n';
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    edited.lines.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
  return edited;
}

std::string EditedText::joined() const {
  std::string text;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    text += lines[i];
    if (i + 1 < lines.size() || finalNewline) text += '\n';
  }
  return text;
}

std::string formatFixed(double value, int minDecimals) {
  if (value == 0.0) value = 0.0;  // no "-0.000000"
  char buffer[64];
  if (std::isfinite(value) && std::fabs(value) < 1e15) {
    for (int decimals = minDecimals; decimals <= 6; ++decimals) {
      std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
      if (std::strtod(buffer, nullptr) == value) return buffer;
    }
  }
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  return std::string(buffer, end);
}

double roundToMicro(double value) {
  if (!std::isfinite(value) || std::fabs(value) >= 1e15) return value;
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", value);
  return std::strtod(buffer, nullptr);
}

void writeFileAtomically(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : ".";
  OutputTarget out(OutputFolder(folder), file.filename().string());
  if (std::fwrite(text.data(), 1, text.size(), out.stream()) != text.size())
    throw std::runtime_error(file.string() + ": cannot write the file");
  out.commit();
}

}  // namespace hirsute
