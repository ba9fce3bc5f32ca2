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
#include <numeric>
#include <set>
#include <string_view>
#include <tuple>
#include <unistd.h>
#include <utility>

#include "hirsute/core/model_folder.h"
#include "mesh_parameterisation.h"

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
// column before Assimp (which would read it as a number of its own) sees it. Returns the OBJ's
// triangles (its faces, triangulated).
std::size_t checkObjCoordinates(const std::string& text, const fs::path& file) {
  std::size_t triangles = 0;
  int line = 1;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view row(text.data() + start, end - start);
    if (row.size() > 2 && row[0] == 'f' && (row[1] == ' ' || row[1] == '\t')) {
      // A face of n corners is n − 2 triangles.
      std::size_t corners = 0;
      for (std::size_t i = 1; i < row.size();) {
        while (i < row.size() && (row[i] == ' ' || row[i] == '\t' || row[i] == '\r')) ++i;
        if (i >= row.size()) break;
        ++corners;
        while (i < row.size() && row[i] != ' ' && row[i] != '\t' && row[i] != '\r') ++i;
      }
      if (corners > 2) triangles += corners - 2;
    }
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
  return triangles;
}


// Frames a second at which an animated file's motion is sampled (docs/meshes.md).
constexpr double kAnimationRate = 24;

// A mesh of the file where a node places it.
struct Instance {
  const aiNode* node = nullptr;
  const aiMesh* mesh = nullptr;
};

void collectInstances(const aiScene& scene, const aiNode* node, std::vector<Instance>& out) {
  if (node == nullptr) return;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const aiMesh* mesh = scene.mMeshes[node->mMeshes[i]];
    if ((mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) != 0) out.push_back({node, mesh});
  }
  for (unsigned i = 0; i < node->mNumChildren; ++i) collectInstances(scene, node->mChildren[i], out);
}

// The value of keys at `ticks`: held before the first and after the last, linear between.
template <class Key, class Blend>
auto keyed(const Key* keys, unsigned count, double ticks, Blend blend) {
  if (count == 1 || ticks <= keys[0].mTime) return keys[0].mValue;
  for (unsigned i = 1; i < count; ++i) {
    if (ticks < keys[i].mTime) {
      const double span = keys[i].mTime - keys[i - 1].mTime;
      const auto t = static_cast<ai_real>(span > 0 ? (ticks - keys[i - 1].mTime) / span : 0.0);
      return blend(keys[i - 1].mValue, keys[i].mValue, t);
    }
  }
  return keys[count - 1].mValue;
}

// A node's transform relative to its parent at `ticks`: the animation's keys where it has a
// channel for the node, else the file's.
aiMatrix4x4 localTransform(const aiNode* node, const aiAnimation* animation, double ticks) {
  if (animation != nullptr) {
    for (unsigned c = 0; c < animation->mNumChannels; ++c) {
      const aiNodeAnim* channel = animation->mChannels[c];
      if (channel->mNodeName != node->mName) continue;
      aiVector3D scaling(1, 1, 1), position;
      aiQuaternion rotation;
      aiVector3D restScaling, restPosition;
      aiQuaternion restRotation;
      node->mTransformation.Decompose(restScaling, restRotation, restPosition);
      const auto lerp = [](const aiVector3D& a, const aiVector3D& b, ai_real t) {
        return a + (b - a) * t;
      };
      const auto slerp = [](const aiQuaternion& a, const aiQuaternion& b, ai_real t) {
        aiQuaternion out;
        aiQuaternion::Interpolate(out, a, b, t);
        return out.Normalize();
      };
      position = channel->mNumPositionKeys > 0
                     ? keyed(channel->mPositionKeys, channel->mNumPositionKeys, ticks, lerp)
                     : restPosition;
      rotation = channel->mNumRotationKeys > 0
                     ? keyed(channel->mRotationKeys, channel->mNumRotationKeys, ticks, slerp)
                     : restRotation;
      scaling = channel->mNumScalingKeys > 0
                    ? keyed(channel->mScalingKeys, channel->mNumScalingKeys, ticks, lerp)
                    : restScaling;
      return aiMatrix4x4(scaling, rotation, position);
    }
  }
  return node->mTransformation;
}

aiMatrix4x4 globalTransform(const aiNode* node, const aiAnimation* animation, double ticks) {
  aiMatrix4x4 global = localTransform(node, animation, ticks);
  for (const aiNode* parent = node->mParent; parent != nullptr; parent = parent->mParent) {
    global = localTransform(parent, animation, ticks) * global;
  }
  return global;
}

glm::dvec3 applied(const aiMatrix4x4& m, const aiVector3D& v) {
  return {m.a1 * v.x + m.a2 * v.y + m.a3 * v.z + m.a4, m.b1 * v.x + m.b2 * v.y + m.b3 * v.z + m.b4,
          m.c1 * v.x + m.c2 * v.y + m.c3 * v.z + m.c4};
}

// A normal under the linear part of m (its inverse transpose).
glm::dvec3 appliedToNormal(const aiMatrix4x4& m, const aiVector3D& n) {
  const glm::dmat3 linear(m.a1, m.b1, m.c1, m.a2, m.b2, m.c2, m.a3, m.b3, m.c3);
  const glm::dmat3 normalMatrix =
      glm::determinant(linear) != 0 ? glm::transpose(glm::inverse(linear)) : linear;
  const glm::dvec3 out = normalMatrix * glm::dvec3(n.x, n.y, n.z);
  const double length = glm::length(out);
  return std::isfinite(length) && length > 0 ? out / length : glm::dvec3(0.0);
}

// Every instance's vertices and normals at `ticks`: a skinned mesh by its bones' transforms
// (each bone's node at that time times its offset, weighted), any other by its node's.
void posedVertices(const aiScene& scene, const aiAnimation* animation, double ticks,
                   const std::vector<Instance>& instances, std::vector<glm::dvec3>& positions,
                   std::vector<glm::dvec3>& normals) {
  for (const Instance& instance : instances) {
    const aiMesh& mesh = *instance.mesh;
    const aiMatrix4x4 placed = globalTransform(instance.node, animation, ticks);
    std::vector<double> weight(mesh.mNumVertices, 0.0);
    std::vector<glm::dvec3> skinned(mesh.mNumVertices, glm::dvec3(0.0)),
        skinnedNormals(mesh.mNumVertices, glm::dvec3(0.0));
    for (unsigned b = 0; b < mesh.mNumBones; ++b) {
      const aiBone& bone = *mesh.mBones[b];
      const aiNode* node = scene.mRootNode->FindNode(bone.mName);
      if (node == nullptr) continue;
      const aiMatrix4x4 m = globalTransform(node, animation, ticks) * bone.mOffsetMatrix;
      for (unsigned w = 0; w < bone.mNumWeights; ++w) {
        const aiVertexWeight& vw = bone.mWeights[w];
        if (vw.mVertexId >= mesh.mNumVertices || !(vw.mWeight > 0)) continue;
        weight[vw.mVertexId] += vw.mWeight;
        skinned[vw.mVertexId] += static_cast<double>(vw.mWeight) * applied(m, mesh.mVertices[vw.mVertexId]);
        if (mesh.HasNormals()) {
          skinnedNormals[vw.mVertexId] +=
              static_cast<double>(vw.mWeight) * appliedToNormal(m, mesh.mNormals[vw.mVertexId]);
        }
      }
    }
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      if (weight[v] > 0) {
        positions.push_back(skinned[v] / weight[v]);
        const double length = glm::length(skinnedNormals[v]);
        normals.push_back(length > 0 ? skinnedNormals[v] / length : glm::dvec3(0.0));
      } else {
        positions.push_back(applied(placed, mesh.mVertices[v]));
        normals.push_back(mesh.HasNormals() ? appliedToNormal(placed, mesh.mNormals[v])
                                            : glm::dvec3(0.0));
      }
    }
  }
}

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
    // Counted before Assimp reads it all: a mesh past the limit costs no more than its text.
    if (const std::size_t triangles = checkObjCoordinates(text, file); triangles > maxTriangles) {
      throw DiagnosticError(at(file), fmt::format("the mesh has {} triangles, more than the limit "
                                                  "of {} (raise it with --max-mesh-triangles)",
                                                  triangles, maxTriangles));
    }
  }

  Assimp::Importer importer;
  auto* files = new ConfinedFiles(folder);
  importer.SetIOHandler(files);  // the importer owns it
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      file.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_GenSmoothNormals | aiProcess_LimitBoneWeights |
                         aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  for (const std::string& refused : files->refused()) {
    diagnostics.warn(at(file), "the mesh names " + refused + "; not read");
  }
  if (scene == nullptr) {
    throw DiagnosticError(at(file), fmt::format("cannot read the mesh: {}", importer.GetErrorString()));
  }

  // Every mesh where a node places it (a mesh two nodes name is there twice).
  std::vector<Instance> instances;
  collectInstances(*scene, scene->mRootNode, instances);
  std::size_t faces = 0;
  bool allUvs = true, colours = true;
  for (const Instance& instance : instances) {
    faces += instance.mesh->mNumFaces;
    allUvs = allUvs && instance.mesh->HasTextureCoords(0);
    colours = colours && instance.mesh->HasVertexColors(0);
  }
  if (faces > maxTriangles) {
    throw DiagnosticError(at(file), fmt::format("the mesh has {} triangles, more than the limit of "
                                                "{} (raise it with --max-mesh-triangles)",
                                                faces, maxTriangles));
  }

  SurfaceMeshData data;
  data.fileUvs = allUvs && faces > 0;
  for (const Instance& instance : instances) {
    const aiMesh& mesh = *instance.mesh;
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      if (data.fileUvs) {
        const aiVector3D& t = mesh.mTextureCoords[0][v];
        data.uv.emplace_back(std::isfinite(t.x) ? t.x : 0.0f, std::isfinite(t.y) ? t.y : 0.0f);
      }
      if (colours) {
        const aiColor4D& c = mesh.mColors[0][v];
        data.colours.emplace_back(c.r, c.g, c.b);
      }
    }
  }
  std::uint32_t base = 0;
  for (const Instance& instance : instances) {
    const aiMesh& mesh = *instance.mesh;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      data.indices.insert(data.indices.end(), {base + face.mIndices[0], base + face.mIndices[1],
                                               base + face.mIndices[2]});
    }
    base += mesh.mNumVertices;
  }

  // The positions and normals: at rest, or an animated file's frames at kAnimationRate.
  const aiAnimation* animation = scene->mNumAnimations > 0 ? scene->mAnimations[0] : nullptr;
  std::size_t frames = 1;
  double ticksPerSecond = 1;
  if (animation != nullptr) {
    ticksPerSecond = animation->mTicksPerSecond > 0 ? animation->mTicksPerSecond : 25.0;
    const double seconds = std::max(0.0, animation->mDuration) / ticksPerSecond;
    const double count = std::floor(seconds * kAnimationRate + 1e-9) + 1;
    if (!(count * static_cast<double>(base) <= static_cast<double>(kMaxSequenceVertices))) {
      throw DiagnosticError(at(file), fmt::format("the animation would hold more than {} vertices "
                                                  "over its {:.0f} frames (the limit)",
                                                  kMaxSequenceVertices, count));
    }
    frames = static_cast<std::size_t>(count);
  }
  for (std::size_t k = 0; k < frames; ++k) {
    const double ticks = static_cast<double>(k) / kAnimationRate * ticksPerSecond;
    std::vector<glm::dvec3> positions, normals;
    posedVertices(*scene, animation, ticks, instances, positions, normals);
    for (std::size_t v = 0; v < positions.size(); ++v) {
      const glm::dvec3& p = positions[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw DiagnosticError(at(file), fmt::format("vertex {} has a non-finite coordinate{}", v + 1,
                                                    k > 0 ? fmt::format(" at frame {}", k + 1)
                                                          : std::string()));
      }
    }
    if (k == 0) {
      data.positions = std::move(positions);
      data.normals = std::move(normals);
    } else {
      data.laterPositions.push_back(std::move(positions));
      data.laterNormals.push_back(std::move(normals));
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
  // Sorted by position, equal positions get one number.
  std::vector<std::uint32_t> byPosition(data.positions.size());
  std::iota(byPosition.begin(), byPosition.end(), 0u);
  const auto position = [&](std::uint32_t v) {
    const glm::dvec3& p = data.positions[v];
    return std::make_tuple(p.x, p.y, p.z);
  };
  std::sort(byPosition.begin(), byPosition.end(),
            [&](std::uint32_t a, std::uint32_t b) { return position(a) < position(b); });
  std::vector<std::uint32_t> welded(data.positions.size());
  for (std::size_t i = 0; i < byPosition.size(); ++i) {
    welded[byPosition[i]] = i > 0 && position(byPosition[i]) == position(byPosition[i - 1])
                                ? welded[byPosition[i - 1]]
                                : static_cast<std::uint32_t>(i);
  }
  const double minimumArea = 1e-14 * diagonal * diagonal;
  std::size_t degenerate = 0;
  std::vector<std::uint32_t> kept;
  kept.reserve(data.indices.size());
  std::vector<std::uint64_t> edges;  // (smaller welded end << 32) | larger, one per side
  edges.reserve(data.indices.size());
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
      edges.push_back(static_cast<std::uint64_t>(std::min(p, q)) << 32 | std::max(p, q));
    }
  }
  data.indices = std::move(kept);
  if (degenerate > 0) {
    diagnostics.warn(at(file), fmt::format("{} degenerate triangle{} (no area) left out",
                                           degenerate, degenerate == 1 ? "" : "s"));
  }
  if (data.indices.empty()) throw DiagnosticError(at(file), "the mesh has no triangle with an area");
  std::sort(edges.begin(), edges.end());
  std::size_t shared = 0;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    shared += j - i > 2;
    i = j;
  }
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
  // An animated file's later frames: the same, on their own positions.
  for (std::size_t k = 0; k < data.laterPositions.size(); ++k) {
    const std::vector<glm::dvec3>& positions = data.laterPositions[k];
    std::vector<glm::dvec3>& normals = data.laterNormals[k];
    if (std::all_of(normals.begin(), normals.end(),
                    [](const glm::dvec3& n) { return n != glm::dvec3(0.0); })) {
      continue;
    }
    std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
    for (std::size_t t = 0; t + 2 < data.indices.size(); t += 3) {
      const std::uint32_t a = data.indices[t], b = data.indices[t + 1], c = data.indices[t + 2];
      const glm::dvec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
      for (std::uint32_t v : {a, b, c}) sum[v] += n;
    }
    for (std::size_t v = 0; v < normals.size(); ++v) {
      if (normals[v] != glm::dvec3(0.0)) continue;
      const double length = glm::length(sum[v]);
      normals[v] = length > 0 ? sum[v] / length : glm::dvec3(0, 0, 1);
    }
  }

  if (!data.fileUvs &&
      parameteriseDisc(data.positions, data.indices, welded, data.uv)) {
    data.uvSource = MeshUvSource::Conformal;
  } else if (!data.fileUvs) {
    // No (u, v) in the file, and no disc: x and y over their bounds, as cpfg maps one texture
    // over a whole `.s` surface (its `S:` textures).
    data.uvSource = MeshUvSource::Planar;
    const glm::dvec2 low(data.boundsMin), span = glm::max(glm::dvec2(data.boundsMax) - low,
                                                          glm::dvec2(1e-300));
    data.uv.clear();
    for (const glm::dvec3& p : data.positions) data.uv.emplace_back((glm::dvec2(p) - low) / span);
    parameteriseCharts(data.positions, data.indices, welded, data.atlasUv, data.atlasChart);
  }
  return data;
}

SurfaceMeshData loadMeshSequence(const fs::path& pattern, const fs::path& folder,
                                 std::size_t maxTriangles, Diagnostics& diagnostics) {
  const std::string name = pattern.filename().string();
  const std::size_t hashes = name.find('#');
  std::size_t width = 0;
  while (hashes + width < name.size() && name[hashes + width] == '#') ++width;
  const std::string prefix = name.substr(0, hashes), suffix = name.substr(hashes + width);
  if (suffix.find('#') != std::string::npos) {
    throw DiagnosticError(at(pattern), "a mesh sequence's name has one run of '#' (the frame number)");
  }
  // The frame numbers there are: prefix, at least `width` digits, suffix.
  const fs::path parent = pattern.parent_path().empty() ? fs::path(".") : pattern.parent_path();
  std::vector<long> numbers;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(parent, error)) {
    const std::string file = entry.path().filename().string();
    if (file.size() < prefix.size() + width + suffix.size() || file.rfind(prefix, 0) != 0 ||
        file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0) {
      continue;
    }
    const std::string digits = file.substr(prefix.size(), file.size() - prefix.size() - suffix.size());
    if (digits.size() < width || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); })) {
      continue;
    }
    if (digits.size() > width && digits.front() == '0') continue;
    numbers.push_back(std::stol(digits));
  }
  std::sort(numbers.begin(), numbers.end());
  if (numbers.empty()) {
    throw DiagnosticError(at(pattern), fmt::format("no frame of the mesh sequence (files {}{}{})",
                                                   prefix, std::string(width, '0'), suffix));
  }
  const auto frameFile = [&](long number) {
    std::string digits = std::to_string(number);
    if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
    return parent / (prefix + digits + suffix);
  };
  SurfaceMeshData data = loadMeshFile(frameFile(numbers.front()), folder, maxTriangles, diagnostics);
  for (std::size_t k = 1; k < numbers.size(); ++k) {
    if (numbers[k] != numbers[k - 1] + 1) {
      throw DiagnosticError(at(frameFile(numbers[k - 1] + 1)),
                            fmt::format("frame {} of the mesh sequence is missing (frames {} to "
                                        "{} are there)",
                                        numbers[k - 1] + 1, numbers.front(), numbers.back()));
    }
    if ((k + 1) * data.positions.size() > kMaxSequenceVertices) {
      throw DiagnosticError(at(frameFile(numbers[k])),
                            fmt::format("the mesh sequence would hold more than {} vertices over "
                                        "its frames (the limit); use fewer frames or a coarser "
                                        "mesh",
                                        kMaxSequenceVertices));
    }
    // A later frame's own warnings repeat the first's: they are not reported again.
    Diagnostics quiet;
    SurfaceMeshData frame = loadMeshFile(frameFile(numbers[k]), folder, maxTriangles, quiet);
    if (frame.positions.size() != data.positions.size()) {
      throw DiagnosticError(at(frameFile(numbers[k])),
                            fmt::format("this frame of the mesh sequence has {} vertices, the "
                                        "first {}: every frame must have the first one's "
                                        "vertices and triangles",
                                        frame.positions.size(), data.positions.size()));
    }
    data.laterPositions.push_back(std::move(frame.positions));
    data.laterNormals.push_back(std::move(frame.normals));
  }
  return data;
}

}  // namespace hirsute

extern "C" __attribute__((visibility("default"))) const hirsute::MeshFileFunctions*
hirsuteMeshFileFunctions() {
  static const hirsute::MeshFileFunctions functions{&hirsute::isMeshFile, &hirsute::loadMeshFile,
                                                    &hirsute::loadMeshSequence};
  return &functions;
}
