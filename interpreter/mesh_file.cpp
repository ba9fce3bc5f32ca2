// Mesh files read with Assimp, every file they name opened beneath the model's folder
// (mesh_file.h).
#include "hirsute/interpreter/mesh_file.h"

#include <assimp/DefaultLogger.hpp>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <string_view>
#include <tuple>
#include <unistd.h>
#include <utility>

#include "hirsute/core/model_folder.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

SourceLocation at(const fs::path& file, int line = 0, int column = 0) {
  return SourceLocation{std::make_shared<const std::string>(file.string()), line, column};
}

std::string lowerExtension(const fs::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// A whole file in memory, as Assimp reads it.
class MemoryStream : public Assimp::IOStream {
 public:
  explicit MemoryStream(std::string bytes) : bytes_(std::move(bytes)) {}

  size_t Read(void* buffer, size_t size, size_t count) override {
    if (size == 0 || position_ >= bytes_.size()) return 0;
    const size_t whole = std::min(count, (bytes_.size() - position_) / size);
    std::memcpy(buffer, bytes_.data() + position_, whole * size);
    position_ += whole * size;
    return whole;
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    size_t target = 0;
    switch (origin) {
      case aiOrigin_SET: target = offset; break;
      case aiOrigin_CUR: target = position_ + offset; break;
      case aiOrigin_END: target = bytes_.size() - std::min(offset, bytes_.size()); break;
      default: return aiReturn_FAILURE;
    }
    if (target > bytes_.size()) return aiReturn_FAILURE;
    position_ = target;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return position_; }
  size_t FileSize() const override { return bytes_.size(); }
  void Flush() override {}

 private:
  std::string bytes_;
  size_t position_ = 0;
};

// Assimp's file access, confined to the model's folder: a name that leaves it (`..`, an absolute
// name, a link out) or is no regular file is not opened, and is remembered for a warning.
class ConfinedFiles : public Assimp::IOSystem {
 public:
  explicit ConfinedFiles(fs::path folder)
      : folder_(folder.empty() ? fs::path(".") : std::move(folder)),
        root_(folder_.lexically_normal()) {}

  bool Exists(const char* file) const override {
    const std::string name = relativeName(file);
    return !name.empty() && static_cast<bool>(ModelFolder(folder_).open(name, FileAccess::Read));
  }
  char getOsSeparator() const override { return '/'; }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (mode == nullptr || std::strchr(mode, 'w') != nullptr || std::strchr(mode, 'a') != nullptr) {
      return nullptr;
    }
    const std::string name = relativeName(file);
    if (name.empty()) {
      refused_.insert(fmt::format("'{}': it leaves the model's folder", file));
      return nullptr;
    }
    std::string bytes, failure;
    if (!ModelFolder(folder_).read(name, bytes, failure)) {
      if (ModelFolder(folder_).refusal(name).empty()) return nullptr;  // missing: Assimp says so
      refused_.insert(fmt::format("'{}': {}", name, failure));
      return nullptr;
    }
    return new MemoryStream(std::move(bytes));
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

  const std::set<std::string>& refused() const { return refused_; }

 private:
  // The name beneath the folder, empty when it leaves it.
  std::string relativeName(const char* file) const {
    if (file == nullptr || *file == '\0') return {};
    const fs::path path = fs::path(file).lexically_normal();
    const fs::path relative = path.lexically_relative(root_);
    if (relative.empty() || relative.is_absolute()) return {};
    const auto first = relative.begin();
    if (first != relative.end() && *first == "..") return {};
    return relative.string();
  }

  fs::path folder_, root_;
  std::set<std::string> refused_;
};

// An OBJ's coordinates are text: a non-finite or unreadable one is reported at its line and
// column before Assimp (which would read it as a number of its own) sees it.
void checkObjCoordinates(const std::string& text, const fs::path& file) {
  int line = 1;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view row(text.data() + start, end - start);
    const bool coordinates = row.size() > 2 && row[0] == 'v' &&
                             (row[1] == ' ' || row[1] == '\t' ||
                              ((row[1] == 't' || row[1] == 'n') && (row[2] == ' ' || row[2] == '\t')));
    if (coordinates) {
      std::size_t i = row[1] == ' ' || row[1] == '\t' ? 1 : 2;
      while (i < row.size()) {
        while (i < row.size() && (row[i] == ' ' || row[i] == '\t' || row[i] == '\r')) ++i;
        if (i >= row.size()) break;
        std::size_t j = i;
        while (j < row.size() && row[j] != ' ' && row[j] != '\t' && row[j] != '\r') ++j;
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
}

glm::dvec3 toDvec3(const aiVector3D& v) { return {v.x, v.y, v.z}; }

}  // namespace

bool isMeshFile(const fs::path& file) {
  const std::string extension = lowerExtension(file);
  if (extension.empty() || extension == ".s") return false;
  static const Assimp::Importer importer;
  return importer.IsExtensionSupported(extension);
}

SurfaceMeshData loadMeshFile(const fs::path& file, const fs::path& folder,
                             std::size_t maxTriangles, Diagnostics& diagnostics) {
  if (lowerExtension(file) == ".obj") {
    std::string text, failure;
    const fs::path root = folder.empty() ? fs::path(".") : folder;
    if (!ModelFolder(root).read(file.lexically_normal().lexically_relative(root.lexically_normal()).string(),
                                text, failure)) {
      throw DiagnosticError(at(file), "cannot read the mesh: " + failure);
    }
    checkObjCoordinates(text, file);
  }

  Assimp::Importer importer;
  auto* files = new ConfinedFiles(folder);
  importer.SetIOHandler(files);  // the importer owns it
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      file.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_PreTransformVertices | aiProcess_GenSmoothNormals |
                         aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  for (const std::string& refused : files->refused()) {
    diagnostics.warn(at(file), "the mesh names " + refused + "; not read");
  }
  if (scene == nullptr) {
    throw DiagnosticError(at(file), fmt::format("cannot read the mesh: {}", importer.GetErrorString()));
  }

  std::size_t faces = 0;
  bool allUvs = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
    faces += mesh.mNumFaces;
    allUvs = allUvs && mesh.HasTextureCoords(0);
  }
  if (faces > maxTriangles) {
    throw DiagnosticError(at(file), fmt::format("the mesh has {} triangles, more than the limit of "
                                                "{} (raise it with --max-mesh-triangles)",
                                                faces, maxTriangles));
  }

  SurfaceMeshData data;
  data.fileUvs = allUvs && faces > 0;
  bool colours = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) != 0) colours = colours && mesh.HasVertexColors(0);
  }
  std::size_t degenerate = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
    const auto base = static_cast<std::uint32_t>(data.positions.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const glm::dvec3 p = toDvec3(mesh.mVertices[v]);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw DiagnosticError(at(file), fmt::format("vertex {} of mesh '{}' has a non-finite "
                                                    "coordinate",
                                                    v + 1, mesh.mName.C_Str()));
      }
      data.positions.push_back(p);
      glm::dvec3 n = mesh.HasNormals() ? toDvec3(mesh.mNormals[v]) : glm::dvec3(0.0);
      const double length = glm::length(n);
      data.normals.push_back(std::isfinite(length) && length > 0 ? n / length : glm::dvec3(0.0));
      if (data.fileUvs) {
        const aiVector3D& t = mesh.mTextureCoords[0][v];
        data.uv.emplace_back(std::isfinite(t.x) ? t.x : 0.0f, std::isfinite(t.y) ? t.y : 0.0f);
      }
      if (colours) {
        const aiColor4D& c = mesh.mColors[0][v];
        data.colours.emplace_back(c.r, c.g, c.b);
      }
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      data.indices.insert(data.indices.end(), {base + face.mIndices[0], base + face.mIndices[1],
                                               base + face.mIndices[2]});
    }
  }
  if (data.positions.empty() || data.indices.empty()) {
    throw DiagnosticError(at(file), "the mesh has no triangles");
  }

  data.boundsMin = data.boundsMax = data.positions.front();
  for (const glm::dvec3& p : data.positions) {
    data.boundsMin = glm::min(data.boundsMin, p);
    data.boundsMax = glm::max(data.boundsMax, p);
  }
  const double diagonal = glm::length(data.boundsMax - data.boundsMin);
  if (!(diagonal > 0)) throw DiagnosticError(at(file), "the mesh's vertices are all one point");

  // Vertices welded by position: the file's seams (UV cuts, hard edges) split vertices that
  // are one point of the surface, and its manifoldness is the welded mesh's.
  std::map<std::tuple<double, double, double>, std::uint32_t> weld;
  std::vector<std::uint32_t> welded(data.positions.size());
  for (std::size_t v = 0; v < data.positions.size(); ++v) {
    const glm::dvec3& p = data.positions[v];
    welded[v] = weld.emplace(std::make_tuple(p.x, p.y, p.z), static_cast<std::uint32_t>(weld.size()))
                    .first->second;
  }
  const double minimumArea = 1e-14 * diagonal * diagonal;
  std::vector<std::uint32_t> kept;
  kept.reserve(data.indices.size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t + 2 < data.indices.size(); t += 3) {
    const std::uint32_t a = data.indices[t], b = data.indices[t + 1], c = data.indices[t + 2];
    const double area = 0.5 * glm::length(glm::cross(data.positions[b] - data.positions[a],
                                                      data.positions[c] - data.positions[a]));
    if (welded[a] == welded[b] || welded[b] == welded[c] || welded[a] == welded[c] ||
        !(area > minimumArea)) {
      ++degenerate;
      continue;
    }
    kept.insert(kept.end(), {a, b, c});
    for (auto [p, q] : {std::pair(welded[a], welded[b]), std::pair(welded[b], welded[c]),
                        std::pair(welded[c], welded[a])}) {
      ++edges[std::minmax(p, q)];
    }
  }
  data.indices = std::move(kept);
  if (degenerate > 0) {
    diagnostics.warn(at(file), fmt::format("{} degenerate triangle{} (no area) left out",
                                           degenerate, degenerate == 1 ? "" : "s"));
  }
  if (data.indices.empty()) throw DiagnosticError(at(file), "the mesh has no triangle with an area");
  const auto shared = static_cast<std::size_t>(
      std::count_if(edges.begin(), edges.end(), [](const auto& edge) { return edge.second > 2; }));
  if (shared > 0) {
    diagnostics.warn(at(file), fmt::format("{} edge{} shared by more than two triangles "
                                           "(non-manifold); drawn and covered as they are",
                                           shared, shared == 1 ? " is" : "s are"));
  }

  // A vertex without a usable normal takes the area-weighted normal of its triangles.
  std::vector<glm::dvec3> faceSum(data.positions.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < data.indices.size(); t += 3) {
    const std::uint32_t a = data.indices[t], b = data.indices[t + 1], c = data.indices[t + 2];
    const glm::dvec3 n = glm::cross(data.positions[b] - data.positions[a],
                                    data.positions[c] - data.positions[a]);
    for (std::uint32_t v : {a, b, c}) faceSum[v] += n;
  }
  for (std::size_t v = 0; v < data.normals.size(); ++v) {
    if (data.normals[v] != glm::dvec3(0.0)) continue;
    const double length = glm::length(faceSum[v]);
    data.normals[v] = length > 0 ? faceSum[v] / length : glm::dvec3(0, 0, 1);
  }

  if (!data.fileUvs) {
    // No (u, v) in the file: x and y over their bounds, as cpfg maps one texture over a whole
    // `.s` surface (its `S:` textures).
    const glm::dvec2 low(data.boundsMin), span = glm::max(glm::dvec2(data.boundsMax) - low,
                                                          glm::dvec2(1e-300));
    data.uv.clear();
    for (const glm::dvec3& p : data.positions) data.uv.emplace_back((glm::dvec2(p) - low) / span);
  }
  return data;
}

}  // namespace hirsute
