#include "hirsute/environment/exchange_text.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace hirsute {
namespace {

void appendG(std::string& out, float value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", static_cast<double>(value));
  out += buffer;
}

void appendParameters(std::string& out, const float* values, std::size_t count) {
  if (count == 0) return;
  out += '(';
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) out += ',';
    appendG(out, values[i]);
  }
  out += ')';
}

// The f32 values the turtle line of `which` formats.
std::array<double, 3> turtleValues(const TurtleState& t, int which) {
  const auto f32 = [](double v) { return static_cast<double>(static_cast<float>(v)); };
  const auto vector = [&](const glm::dvec3& v) {
    return std::array<double, 3>{f32(v.x), f32(v.y), f32(v.z)};
  };
  switch (which) {
    case kPosition:
      return vector(t.position);
    case kHeading:
      return vector(t.heading);
    case kLeft:
      return vector(t.left);
    case kUp:
      return vector(t.up);
    case kLineWidth:
      return {f32(t.lineWidth), 0, 0};
    default:
      return {f32(t.scale), 0, 0};
  }
}

// The lines of `text`, each without its newline.
std::vector<std::string_view> lines(std::string_view text) {
  std::vector<std::string_view> out;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    out.push_back(text.substr(0, end));
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return out;
}

// Values between `(` and `)` split at commas: atof to float, empty pieces unset.
std::vector<std::optional<float>> parenthesisedValues(std::string_view inside) {
  std::vector<std::optional<float>> values;
  while (true) {
    const std::size_t comma = inside.find(',');
    const std::string piece(inside.substr(0, comma));
    if (piece.empty()) {
      values.push_back(std::nullopt);
    } else {
      values.push_back(static_cast<float>(std::atof(piece.c_str())));
    }
    if (comma == std::string_view::npos) break;
    inside.remove_prefix(comma + 1);
  }
  return values;
}

// The parameters between an answer's parentheses, each empty (no value) or a number with
// nothing after it but blanks; false when one is neither.
bool allNumbers(std::string_view inside, std::vector<std::optional<float>>& values) {
  values = parenthesisedValues(inside);
  while (true) {
    const std::size_t comma = inside.find(',');
    const std::string piece(inside.substr(0, comma));
    if (piece.find_first_not_of(" \t\r") != std::string::npos) {
      char* end = nullptr;
      std::strtod(piece.c_str(), &end);
      if (end == piece.c_str() || std::strspn(end, " \t\r") != std::strlen(end)) return false;
    }
    if (comma == std::string_view::npos) return true;
    inside.remove_prefix(comma + 1);
  }
}

// A module at `at` of `line`: its symbol (two characters for `~` and `@`) and its parameters;
// `at` moves past it.
ModuleValues readModule(std::string_view line, std::size_t& at) {
  ModuleValues m;
  if (at >= line.size()) return m;
  m.symbols = std::string(1, line[at++]);
  if ((m.symbols[0] == '~' || m.symbols[0] == '@') && at < line.size()) m.symbols += line[at++];
  if (at < line.size() && line[at] == '(') {
    const std::size_t close = line.find(')', at);
    const std::size_t end = close == std::string_view::npos ? line.size() : close;
    m.values = parenthesisedValues(line.substr(at + 1, end - at - 1));
    at = close == std::string_view::npos ? line.size() : close + 1;
  }
  return m;
}

bool isControl(std::string_view line) {
  return line.substr(0, 8) == "Control:";
}

}  // namespace

void appendQueryRecord(std::string& batch, unsigned long id, const EnvironmentQuery& q,
                       const CommunicationFile& file) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%lu E", id);
  batch += buffer;
  // cpfg sends at most 20 parameters of a module (CMAXPARAMS of its library).
  constexpr std::size_t kMaxSent = 20;
  appendParameters(batch, q.parameters, std::min(q.count, kMaxSent));
  if (file.followingModule && !q.followingSymbols.empty()) {
    batch += q.followingSymbols;
    appendParameters(batch, q.followingParameters, std::min(q.followingCount, kMaxSent));
  }
  batch += '\n';
  for (int v = 0; v < kTurtleValues; ++v) {
    const TurtleFormat& f = file.turtle[static_cast<std::size_t>(v)];
    if (!f.present) continue;
    const std::array<double, 3> x = turtleValues(*q.turtle, v);
    // The format was checked when the file was read: at most three floating conversions.
    const int n = std::snprintf(nullptr, 0, f.format.c_str(), x[0], x[1], x[2]);
    if (n > 0) {
      std::string text(static_cast<std::size_t>(n) + 1, '\0');
      std::snprintf(text.data(), text.size(), f.format.c_str(), x[0], x[1], x[2]);
      text.resize(static_cast<std::size_t>(n));
      batch += text;
    }
    batch += '\n';
  }
}

std::string batchEndLine(int step) {
  return "Control: 5 " + std::to_string(step) + "\n";
}

std::vector<AnswerRecord> parseAnswers(std::string_view text, std::vector<std::string>* rejected) {
  std::vector<AnswerRecord> out;
  for (std::string_view line : lines(text)) {
    if (isControl(line)) break;
    std::size_t at = line.find_first_not_of(" ,;:");
    if (at == std::string_view::npos) continue;
    const std::size_t tokenEnd = std::min(line.find_first_of(" ,;:", at), line.size());
    const std::string token(line.substr(at, tokenEnd - at));
    const std::size_t e = line.find('E', tokenEnd);
    if (e == std::string_view::npos) {
      if (rejected) rejected->push_back(std::string(line));
      continue;
    }
    // The id is a whole number, and parameters in parentheses are closed and numbers (or empty):
    // `zz E(1,2` or `1 E((((` is no answer.
    const bool numbered = token.find_first_not_of("0123456789") == std::string::npos;
    AnswerRecord record;
    record.id = std::strtoul(token.c_str(), nullptr, 10);
    bool readable = numbered;
    if (readable && e + 1 < line.size() && line[e + 1] == '(') {
      const std::size_t close = line.find(')', e + 2);
      readable = close != std::string_view::npos &&
                 allNumbers(line.substr(e + 2, close - e - 2), record.values);
    }
    if (!readable) {
      if (rejected) rejected->push_back(std::string(line));
      continue;
    }
    out.push_back(std::move(record));
  }
  return out;
}

int QueryReader::read(std::string_view text, std::vector<EnvironmentQueryRecord>& out) {
  std::vector<std::string_view> all = lines(text);
  for (std::size_t i = 0; i < all.size(); ++i) {
    std::string_view line = all[i];
    if (isControl(line)) {
      return std::atoi(std::string(line.substr(8)).c_str());
    }
    EnvironmentQueryRecord r;
    r.id = std::strtoul(std::string(line).c_str(), nullptr, 10);
    std::size_t at = line.find('E');
    if (at != std::string_view::npos) {
      r.module = readModule(line, at);
      if (file_.followingModule) r.following = readModule(line, at);
    }
    for (int v = 0; v < kTurtleValues; ++v) {
      const TurtleFormat& f = file_.turtle[static_cast<std::size_t>(v)];
      if (!f.present) continue;
      std::string_view valueLine = i + 1 < all.size() ? all[++i] : std::string_view();
      const std::string rest(valueLine.substr(std::min(f.firstConversion, valueLine.size())));
      std::array<float, 3>& stale = stale_[static_cast<std::size_t>(v)];
      const char* p = rest.c_str();
      for (int k = 0; k < (v < kLineWidth ? 3 : 1); ++k) {
        char* end = nullptr;
        const float value = std::strtof(p, &end);
        if (end == p) break;
        stale[static_cast<std::size_t>(k)] = value;
        p = end;
      }
      r.turtle[static_cast<std::size_t>(v)] = stale;
      r.counts[static_cast<std::size_t>(v)] = f.conversions;
    }
    out.push_back(std::move(r));
  }
  return -1;
}

void appendAnswerRecord(std::string& answers, unsigned long id,
                        const std::vector<std::optional<float>>& values) {
  if (values.empty()) return;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%lu E(", id);
  answers += buffer;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) answers += ',';
    if (values[i]) appendG(answers, *values[i]);
  }
  answers += ")\n";
}

}  // namespace hirsute
