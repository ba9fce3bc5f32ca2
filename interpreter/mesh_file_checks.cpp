// Cheap checks of a mesh file's bytes before Assimp reads them (mesh_file_checks.h).
#include "mesh_file_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

SourceLocation at(const fs::path& file, int line = 0, int column = 0) {
  return SourceLocation{std::make_shared<const std::string>(file.string()), line, column};
}

[[noreturn]] void tooManyTriangles(const fs::path& file, std::size_t triangles,
                                   std::size_t maxTriangles) {
  throw DiagnosticError(at(file), fmt::format("the mesh has {} triangles, more than the limit of "
                                              "{} (raise it with --max-mesh-triangles)",
                                              triangles, maxTriangles));
}

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// --- OBJ -----------------------------------------------------------------------------------

// An OBJ's coordinates are text: a non-finite or unreadable one is reported at its line and
// column before Assimp (which would read it as a number of its own) sees it. Its faces are
// counted as triangles, its groups against kMaxObjGroups.
void checkObj(const std::string& text, const fs::path& file, std::size_t maxTriangles) {
  std::size_t triangles = 0, groups = 0;
  int line = 1;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view row(text.data() + start, end - start);
    const std::string_view keyword =
        row.substr(0, std::min(row.size(), row.find_first_of(" \t\r")));
    if (keyword == "f") {
      // A face of n corners is n − 2 triangles.
      std::size_t corners = 0;
      for (std::size_t i = 1; i < row.size();) {
        while (i < row.size() && isBlank(row[i])) ++i;
        if (i >= row.size()) break;
        ++corners;
        while (i < row.size() && !isBlank(row[i])) ++i;
      }
      if (corners > 2) triangles += corners - 2;
    } else if (keyword == "g" || keyword == "o" || keyword == "usemtl") {
      if (++groups > kMaxObjGroups) {
        throw DiagnosticError(
            at(file, line, 1),
            fmt::format("more than {} groups, objects or materials ('g', 'o', 'usemtl'): a mesh "
                        "is read as one surface, and each group would cost a mesh of its own",
                        kMaxObjGroups));
      }
    } else if (keyword == "v" || keyword == "vt" || keyword == "vn") {
      std::size_t i = keyword.size();
      while (i < row.size()) {
        while (i < row.size() && isBlank(row[i])) ++i;
        if (i >= row.size()) break;
        std::size_t j = i;
        while (j < row.size() && !isBlank(row[j])) ++j;
        const std::string word(row.substr(i, j - i));
        char* stop = nullptr;
        const double value = std::strtod(word.c_str(), &stop);
        if (stop != word.c_str() + word.size() || !std::isfinite(value)) {
          throw DiagnosticError(at(file, line, static_cast<int>(i) + 1),
                                fmt::format("'{}' is not a finite coordinate", word));
        }
        i = j;
      }
    }
    ++line;
    start = end + 1;
  }
  if (triangles > maxTriangles) tooManyTriangles(file, triangles, maxTriangles);
}

// --- PLY -----------------------------------------------------------------------------------

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool plyType(std::string_view name, PlyType& type) {
  static const std::pair<const char*, PlyType> kNames[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [word, value] : kNames) {
    if (name == word) {
      type = value;
      return true;
    }
  }
  return false;
}

std::size_t plySize(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

bool plyInteger(PlyType type) {
  return type != PlyType::Float32 && type != PlyType::Float64;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;
  bool list = false;
  PlyType countType = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  int line = 0;
  std::vector<PlyProperty> properties;
};

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isBlank(line[i])) ++i;
    std::size_t j = i;
    while (j < line.size() && !isBlank(line[j])) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

bool unsignedNumber(std::string_view word, std::uint64_t& value) {
  if (word.empty() || word.size() > 19) return false;
  value = 0;
  for (char c : word) {
    if (c < '0' || c > '9') return false;
    value = value * 10 + static_cast<std::uint64_t>(c - '0');
  }
  return true;
}

// The body of a PLY walked value by value, ASCII (words with their lines and columns) or
// binary (bytes in either order).
class PlyBody {
 public:
  PlyBody(const std::string& bytes, std::size_t start, int line, bool ascii, bool bigEndian,
          const fs::path& file)
      : bytes_(bytes),
        at_(start),
        line_(line),
        lineStart_(start),
        ascii_(ascii),
        bigEndian_(bigEndian),
        file_(file) {}

  // The next value as a number; `where` is its line and column (ASCII) or byte offset.
  double next(PlyType type, const char* what) {
    if (ascii_) {
      while (at_ < bytes_.size() && (isBlank(bytes_[at_]) || bytes_[at_] == '\n')) {
        if (bytes_[at_] == '\n') {
          ++line_;
          lineStart_ = at_ + 1;
        }
        ++at_;
      }
      if (at_ >= bytes_.size()) ended(what);
      wordLine_ = line_;
      wordColumn_ = static_cast<int>(at_ - lineStart_) + 1;
      std::size_t end = at_;
      while (end < bytes_.size() && !isBlank(bytes_[end]) && bytes_[end] != '\n') ++end;
      const std::string word = bytes_.substr(at_, std::min<std::size_t>(end - at_, 64));
      at_ = end;
      char* stop = nullptr;
      const double value = std::strtod(word.c_str(), &stop);
      if (word.empty() || stop != word.c_str() + word.size() ||
          (plyInteger(type) && (!std::isfinite(value) || value != std::floor(value)))) {
        fail(fmt::format("'{}' is not {} ({})", word, plyInteger(type) ? "an integer" : "a number",
                         what));
      }
      return value;
    }
    const std::size_t size = plySize(type);
    if (bytes_.size() - at_ < size) ended(what);
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + at_, size);
    at_ += size;
    if (bigEndian_) std::reverse(raw, raw + size);
    switch (type) {
      case PlyType::Int8:
        return static_cast<std::int8_t>(raw[0]);
      case PlyType::UInt8:
        return raw[0];
      case PlyType::Int16: {
        std::int16_t v;
        std::memcpy(&v, raw, 2);
        return v;
      }
      case PlyType::UInt16: {
        std::uint16_t v;
        std::memcpy(&v, raw, 2);
        return v;
      }
      case PlyType::Int32: {
        std::int32_t v;
        std::memcpy(&v, raw, 4);
        return v;
      }
      case PlyType::UInt32: {
        std::uint32_t v;
        std::memcpy(&v, raw, 4);
        return v;
      }
      case PlyType::Float32: {
        float v;
        std::memcpy(&v, raw, 4);
        return v;
      }
      case PlyType::Float64: {
        double v;
        std::memcpy(&v, raw, 8);
        return v;
      }
    }
    return 0;
  }

  std::size_t left() const { return bytes_.size() - at_; }

  [[noreturn]] void fail(const std::string& message) const {
    if (ascii_) throw DiagnosticError(at(file_, wordLine_, wordColumn_), message);
    throw DiagnosticError(at(file_), fmt::format("at byte {}: {}", at_, message));
  }

 private:
  [[noreturn]] void ended(const char* what) const {
    throw DiagnosticError(
        at(file_, ascii_ ? line_ : 0),
        fmt::format("the file ends before its header's elements do (at {})", what));
  }

  const std::string& bytes_;
  std::size_t at_;
  int line_;
  std::size_t lineStart_;
  int wordLine_ = 0, wordColumn_ = 0;
  bool ascii_, bigEndian_;
  const fs::path& file_;
};

// A PLY's header read strictly, and its body walked element by element: every row there, every
// list's length within the file, every face of at least 3 corners whose indices name vertices
// there, every ASCII coordinate finite; its triangles counted.
void checkPly(const std::string& bytes, const fs::path& file, std::size_t maxTriangles) {
  std::vector<PlyElement> elements;
  bool ascii = false, bigEndian = false, format = false;
  std::size_t start = 0;
  int line = 0;
  bool ended = false;
  while (!ended) {
    if (start >= bytes.size() || line > 100'000) {
      throw DiagnosticError(at(file, line), "the PLY header has no 'end_header' line");
    }
    std::size_t end = bytes.find('\n', start);
    if (end == std::string::npos) end = bytes.size();
    ++line;
    const std::vector<std::string_view> w =
        words(std::string_view(bytes).substr(start, end - start));
    start = end + 1;
    const auto fail = [&](const std::string& message) {
      throw DiagnosticError(at(file, line, 1), message);
    };
    if (line == 1) {
      if (w.size() != 1 || w[0] != "ply") fail("a PLY file begins with the line 'ply'");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (w.size() != 3 ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian")) {
        fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      }
      ascii = w[1] == "ascii";
      bigEndian = w[1] == "binary_big_endian";
      format = true;
    } else if (w[0] == "element") {
      PlyElement element;
      if (w.size() != 3 || !unsignedNumber(w[2], element.count)) {
        fail("expected 'element NAME COUNT'");
      }
      element.name = std::string(w[1]);
      element.line = line;
      elements.push_back(std::move(element));
    } else if (w[0] == "property") {
      if (elements.empty()) fail("a property before any element");
      PlyProperty property;
      if (w.size() == 5 && w[1] == "list") {
        property.list = true;
        if (!plyType(w[2], property.countType) || !plyType(w[3], property.type) ||
            !plyInteger(property.countType)) {
          fail("expected 'property list COUNT_TYPE TYPE NAME' with an integer COUNT_TYPE");
        }
        property.name = std::string(w[4]);
      } else if (w.size() == 3 && plyType(w[1], property.type)) {
        property.name = std::string(w[2]);
      } else {
        fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
      elements.back().properties.push_back(std::move(property));
    } else if (w[0] == "end_header") {
      ended = true;
    } else {
      fail(fmt::format("'{}' is no PLY header line", w[0]));
    }
  }
  if (!format) throw DiagnosticError(at(file, 1), "the PLY header has no 'format' line");

  PlyBody body(bytes, start, line + 1, ascii, bigEndian, file);
  std::uint64_t vertices = 0, triangles = 0;
  for (const PlyElement& element : elements) {
    // Each row is at least a byte: a count past the file's bytes is refused before Assimp
    // reserves room for it.
    if (element.count > body.left()) {
      throw DiagnosticError(at(file, element.line, 1),
                            fmt::format("element '{}' announces {} rows, more than the file's "
                                        "{} bytes after its header hold",
                                        element.name, element.count, body.left()));
    }
    if (element.properties.empty()) continue;
    const bool isVertex = element.name == "vertex";
    const bool isFace = element.name == "face" || element.name == "tristrips";
    for (std::uint64_t row = 0; row < element.count; ++row) {
      for (const PlyProperty& property : element.properties) {
        const bool coordinate =
            isVertex && (property.name == "x" || property.name == "y" || property.name == "z");
        const bool indices = isFace && property.list &&
                             (property.name == "vertex_indices" || property.name == "vertex_index");
        if (!property.list) {
          const double value = body.next(property.type, property.name.c_str());
          if (coordinate && !std::isfinite(value)) {
            body.fail(fmt::format("vertex {} has the non-finite coordinate {} = {}", row + 1,
                                  property.name, value));
          }
          continue;
        }
        const double count = body.next(property.countType, "a list's length");
        if (count < 0) body.fail(fmt::format("a list of {} values", count));
        const auto n = static_cast<std::uint64_t>(count);
        if (n > body.left())
          body.fail(fmt::format("a list of {} values runs past the file's end", n));
        if (indices && element.name == "face" && n < 3) {
          body.fail(fmt::format("face {} has {} corner{} (a face has at least 3)", row + 1, n,
                                n == 1 ? "" : "s"));
        }
        for (std::uint64_t k = 0; k < n; ++k) {
          const double value = body.next(property.type, property.name.c_str());
          // A triangle strip separates its strips with -1.
          if (indices && !(value >= 0 && value < static_cast<double>(vertices)) &&
              !(element.name == "tristrips" && value == -1)) {
            body.fail(fmt::format("{} {} names vertex {}; there are {} (from 0)", element.name,
                                  row + 1, value, vertices));
          }
        }
        if (indices) triangles += element.name == "face" ? n - 2 : (n > 2 ? n - 2 : 0);
        if (triangles > maxTriangles) tooManyTriangles(file, triangles, maxTriangles);
      }
    }
    if (isVertex) vertices = element.count;
  }
}

// --- JSON (glTF) and GLB ---------------------------------------------------------------------

// One pass over JSON text: its nesting at most kMaxMeshNesting deep, and the node graph of a
// glTF (2.0: `nodes` an array, `children` indices; 1.0: `nodes` an object, `children` names)
// without a cycle and at most kMaxMeshNesting deep. Text that is no JSON ends the pass: Assimp
// says what is wrong with it.
void checkGltfJson(std::string_view text, const fs::path& file, int firstLine) {
  struct Level {
    bool object = false;
    std::string key;        // an object's current key
    std::size_t index = 0;  // an array's current element
  };
  std::vector<Level> stack;
  std::map<std::string, std::vector<std::string>> children;
  int line = firstLine;
  std::size_t lineStart = 0;
  bool expectKey = false;
  const auto location = [&](std::size_t i) {
    return at(file, line, static_cast<int>(i - lineStart) + 1);
  };
  // Where a value at the top of the stack lies: a node's id when it is an element of
  // `children` of a node.
  const auto childOf = [&](std::string& parent) {
    if (stack.size() != 4 || !stack[0].object || stack[0].key != "nodes" || !stack[2].object ||
        stack[2].key != "children" || stack[3].object) {
      return false;
    }
    parent = stack[1].object ? stack[1].key : std::to_string(stack[1].index);
    return true;
  };
  const auto valueDone = [&] {
    if (!stack.empty() && !stack.back().object) ++stack.back().index;
  };
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      lineStart = ++i;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r' || c == ',' || c == ':') {
      if (c == ',' && !stack.empty() && stack.back().object) expectKey = true;
      ++i;
      continue;
    }
    if (c == '{' || c == '[') {
      if (static_cast<int>(stack.size()) >= kMaxMeshNesting) {
        throw DiagnosticError(location(i),
                              fmt::format("the JSON nests more than {} deep", kMaxMeshNesting));
      }
      stack.push_back(Level{c == '{', {}, 0});
      expectKey = c == '{';
      ++i;
      continue;
    }
    if (c == '}' || c == ']') {
      if (stack.empty()) return;
      stack.pop_back();
      expectKey = false;
      valueDone();
      ++i;
      continue;
    }
    if (c == '"') {
      std::string value;
      std::size_t j = i + 1;
      while (j < text.size() && text[j] != '"') {
        if (text[j] == '\\' && j + 1 < text.size()) ++j;
        if (text[j] == '\n') return;
        if (value.size() < 256) value += text[j];
        ++j;
      }
      if (j >= text.size()) return;
      i = j + 1;
      if (expectKey && !stack.empty() && stack.back().object) {
        stack.back().key = std::move(value);
        expectKey = false;
        if (stack.size() == 2 && stack[0].object && stack[0].key == "nodes" && stack[1].object) {
          children[stack[1].key];  // a glTF 1.0 node: known even without children
        }
        continue;
      }
      if (std::string parent; childOf(parent)) children[parent].push_back(value);
      valueDone();
      continue;
    }
    // A number or a literal.
    std::size_t j = i;
    while (j < text.size() && std::strchr(",:]} \t\r\n", text[j]) == nullptr) ++j;
    if (j == i) return;
    const std::string_view word = text.substr(i, j - i);
    if (std::string parent; childOf(parent)) {
      children[parent].emplace_back(word);
    }
    valueDone();
    i = j;
  }

  // The longest chain of children, walked without recursion; a node met again on its own
  // chain is a cycle.
  enum class Mark : std::uint8_t { New, OnChain, Done };
  std::map<std::string, Mark> marks;
  std::map<std::string, int> depth;  // the longest chain below a finished node, itself included
  for (const auto& [root, unused] : children) {
    if (marks[root] != Mark::New) continue;
    std::vector<std::pair<std::string, std::size_t>> chain{{root, 0}};
    marks[root] = Mark::OnChain;
    while (!chain.empty()) {
      auto& [node, next] = chain.back();
      const auto found = children.find(node);
      const std::vector<std::string>* below = found == children.end() ? nullptr : &found->second;
      if (below != nullptr && next < below->size()) {
        const std::string child = (*below)[next++];
        Mark& mark = marks[child];
        if (mark == Mark::OnChain) {
          throw DiagnosticError(at(file), fmt::format("node {} is among its own children's "
                                                      "descendants (a cycle)",
                                                      child));
        }
        if (mark == Mark::New) {
          mark = Mark::OnChain;
          if (static_cast<int>(chain.size()) >= kMaxMeshNesting) {
            throw DiagnosticError(at(file), fmt::format("the node hierarchy is more than {} "
                                                        "nodes deep",
                                                        kMaxMeshNesting));
          }
          chain.emplace_back(child, 0);
        } else if (static_cast<int>(chain.size()) + depth[child] > kMaxMeshNesting) {
          throw DiagnosticError(at(file), fmt::format("the node hierarchy is more than {} nodes "
                                                      "deep",
                                                      kMaxMeshNesting));
        }
        continue;
      }
      int deepest = 0;
      if (below != nullptr) {
        for (const std::string& child : *below) deepest = std::max(deepest, depth[child]);
      }
      depth[node] = deepest + 1;
      marks[node] = Mark::Done;
      chain.pop_back();
    }
  }
}

std::uint32_t littleEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = value << 8 | static_cast<unsigned char>(bytes[at + k]);
  return value;
}

// A binary glTF: its JSON (glTF 2.0's first chunk, or 1.0's content) checked as a .gltf's.
void checkGlb(const std::string& bytes, const fs::path& file) {
  if (bytes.size() < 20) throw DiagnosticError(at(file), "a binary glTF shorter than its header");
  const std::uint32_t version = littleEndian32(bytes, 4);
  const std::uint32_t length = littleEndian32(bytes, 12);
  if (length > bytes.size() - 20) {
    throw DiagnosticError(at(file), fmt::format("the binary glTF's JSON of {} bytes runs past the "
                                                "file's end",
                                                length));
  }
  if (version == 2 && littleEndian32(bytes, 16) != 0x4E4F534Au) {
    throw DiagnosticError(at(file), "the binary glTF's first chunk is not its JSON");
  }
  checkGltfJson(std::string_view(bytes).substr(20, length), file, 1);
}

// --- XML (COLLADA and the other XML formats) -------------------------------------------------

// Elements nested at most kMaxMeshNesting deep (COLLADA's nodes nest as elements).
void checkXmlNesting(const std::string& text, const fs::path& file) {
  int depth = 0, line = 1;
  std::size_t lineStart = 0;
  const auto skipPast = [&](std::size_t from, std::string_view end) {
    const std::size_t found = text.find(end, from);
    const std::size_t to = found == std::string::npos ? text.size() : found + end.size();
    for (std::size_t k = from; k < to; ++k) {
      if (text[k] == '\n') {
        ++line;
        lineStart = k + 1;
      }
    }
    return to;
  };
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == '\n') {
      ++line;
      lineStart = ++i;
      continue;
    }
    if (text[i] != '<') {
      ++i;
      continue;
    }
    const std::string_view rest = std::string_view(text).substr(i);
    if (rest.substr(0, 4) == "<!--") {
      i = skipPast(i + 4, "-->");
    } else if (rest.substr(0, 9) == "<![CDATA[") {
      i = skipPast(i + 9, "]]>");
    } else if (rest.substr(0, 2) == "<?") {
      i = skipPast(i + 2, "?>");
    } else if (rest.substr(0, 2) == "<!") {
      const std::size_t close = text.find('>', i);
      const std::size_t bracket = text.find('[', i);
      i = bracket < close ? skipPast(i + 2, "]>") : skipPast(i + 2, ">");
    } else if (rest.substr(0, 2) == "</") {
      depth = std::max(0, depth - 1);
      i = skipPast(i + 2, ">");
    } else {
      const int column = static_cast<int>(i - lineStart) + 1, startLine = line;
      // The start tag, its quoted values skipped whole.
      std::size_t k = i + 1;
      char quote = 0;
      for (; k < text.size(); ++k) {
        if (text[k] == '\n') {
          ++line;
          lineStart = k + 1;
        }
        if (quote != 0) {
          if (text[k] == quote) quote = 0;
        } else if (text[k] == '"' || text[k] == '\'') {
          quote = text[k];
        } else if (text[k] == '>') {
          break;
        }
      }
      const bool empty = k < text.size() && k > i + 1 && text[k - 1] == '/';
      if (!empty && ++depth > kMaxMeshNesting) {
        throw DiagnosticError(
            at(file, startLine, column),
            fmt::format("the XML's elements nest more than {} deep", kMaxMeshNesting));
      }
      i = k + 1;
    }
  }
}

}  // namespace

void checkMeshFileBytes(const std::string& bytes, const fs::path& file, std::size_t maxTriangles) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".obj") {
    checkObj(bytes, file, maxTriangles);
    return;
  }
  // The others by what they hold, as Assimp may take a file for what it holds.
  std::size_t first = bytes.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  while (first < bytes.size() && std::strchr(" \t\r\n", bytes[first]) != nullptr) ++first;
  const std::string_view content = std::string_view(bytes).substr(first);
  // Assimp reads any file that begins with "ply" as PLY (`plyply` too, and past a header line it
  // cannot read, out of bounds): such a file, and every .ply, must have PLY's header whole.
  std::string start = bytes.substr(0, 3);
  std::transform(start.begin(), start.end(), start.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".ply" || start == "ply") {
    checkPly(bytes, file, maxTriangles);
  } else if (bytes.rfind("glTF", 0) == 0) {
    checkGlb(bytes, file);
  } else if (content.substr(0, 1) == "{") {
    checkGltfJson(bytes, file, 1);
  } else if (content.substr(0, 1) == "<") {
    checkXmlNesting(bytes, file);
  }
}

}  // namespace hirsute
