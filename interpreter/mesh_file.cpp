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
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <numeric>
#include <set>
#include <string_view>
#include <system_error>
#include <tuple>
#include <unistd.h>
#include <utility>

#include "hirsute/core/isolated_call.h"
#include "hirsute/core/model_folder.h"
#include "mesh_file_checks.h"
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
  // `name` (beneath the folder) is served from `bytes`, read once and checked before Assimp.
  ConfinedFiles(fs::path folder, std::string name, const std::string& bytes)
      : folder_(folder.empty() ? fs::path(".") : std::move(folder)),
        root_(folder_.lexically_normal()),
        readName_(std::move(name)),
        readBytes_(bytes) {}

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
    if (name == readName_) return new MemoryStream(readBytes_);
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
  std::string readName_;
  const std::string& readBytes_;
  std::set<std::string> refused_;
};

// Frames a second at which an animated file's motion is sampled (docs/meshes.md).
constexpr double kAnimationRate = 24;

// A mesh of the file where a node places it.
struct Instance {
  const aiNode* node = nullptr;
  const aiMesh* mesh = nullptr;
};

// Every node's meshes, depth first, without recursion (a hierarchy may be deep).
void collectInstances(const aiScene& scene, const aiNode* root, std::vector<Instance>& out) {
  std::vector<const aiNode*> pending{root};
  while (!pending.empty()) {
    const aiNode* node = pending.back();
    pending.pop_back();
    if (node == nullptr) continue;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const aiMesh* mesh = scene.mMeshes[node->mMeshes[i]];
      if ((mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) != 0) out.push_back({node, mesh});
    }
    for (unsigned i = node->mNumChildren; i > 0; --i) pending.push_back(node->mChildren[i - 1]);
  }
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

// The whole reading of one mesh file, in this process: its bytes checked (mesh_file_checks.h),
// Assimp, and the checks and completions of the mesh it gives.
SurfaceMeshData readMeshFile(const fs::path& file, const fs::path& folder, std::size_t maxTriangles,
                             Diagnostics& diagnostics) {
  const fs::path root = folder.empty() ? fs::path(".") : folder;
  const std::string name =
      file.lexically_normal().lexically_relative(root.lexically_normal()).string();
  std::string bytes, failure;
  if (!ModelFolder(root).read(name, bytes, failure)) {
    throw DiagnosticError(at(file), "cannot read the mesh: " + failure);
  }
  checkMeshFileBytes(bytes, file, maxTriangles);

  Assimp::Importer importer;
  auto* files = new ConfinedFiles(folder, name, bytes);
  importer.SetIOHandler(files);  // the importer owns it
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read and validated first, the rest of the steps after the positions are checked: joining
  // identical vertices would take a non-finite one for another and leave a degenerate triangle.
  const aiScene* scene = importer.ReadFile(file.string(), aiProcess_ValidateDataStructure);
  for (const std::string& refused : files->refused()) {
    diagnostics.warn(at(file), "the mesh names " + refused + "; not read");
  }
  const auto failed = [&] {
    const std::string why = importer.GetErrorString();
    // Assimp turns running out of memory into its error text.
    if (why.find("bad_alloc") != std::string::npos) throw std::bad_alloc();
    throw DiagnosticError(at(file), fmt::format("cannot read the mesh: {}", why));
  };
  if (scene == nullptr) failed();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw DiagnosticError(at(file), fmt::format("vertex {} of the file's mesh {} has a "
                                                    "non-finite coordinate",
                                                    v + 1, m + 1));
      }
    }
  }
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                       aiProcess_GenSmoothNormals | aiProcess_LimitBoneWeights |
                                       aiProcess_SortByPType);
  if (scene == nullptr) failed();

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
  std::size_t clamped = 0;
  for (const Instance& instance : instances) {
    const aiMesh& mesh = *instance.mesh;
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      if (data.fileUvs) {
        const aiVector3D& t = mesh.mTextureCoords[0][v];
        data.uv.emplace_back(std::isfinite(t.x) ? t.x : 0.0f, std::isfinite(t.y) ? t.y : 0.0f);
      }
      if (colours) {
        // A vertex colour's red blends the key feathers (docs/meshes.md): it is a fraction, and a
        // value just outside [0, 1] (a float file's rounding) is clamped, with a warning.
        const aiColor4D& c = mesh.mColors[0][v];
        const glm::vec3 rgb(c.r, c.g, c.b);
        if (!std::isfinite(rgb.r) || !std::isfinite(rgb.g) || !std::isfinite(rgb.b)) {
          throw DiagnosticError(
              at(file), fmt::format("vertex {} has a non-finite colour", data.colours.size() + 1));
        }
        const glm::vec3 inside = glm::clamp(rgb, 0.0f, 1.0f);
        clamped += inside != rgb;
        data.colours.push_back(inside);
      }
    }
  }
  if (clamped > 0) {
    diagnostics.warn(at(file), fmt::format("{} vertex colour{} outside [0, 1] clamped to it",
                                           clamped, clamped == 1 ? "" : "s"));
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

// --- The child's answer ----------------------------------------------------------------------
// loadMeshFile reads a mesh in a child process (isolated_call.h), which sends back the mesh (or
// its error) and its warnings in this form: 64-bit counts and the vectors' bytes as they lie in
// memory (parent and child are one program). The parent reads it as it would read a file: a
// child that a malformed mesh took over may send anything.

constexpr std::uint64_t kAnswerMesh = 1, kAnswerError = 2;

class AnswerWriter {
 public:
  void number(std::uint64_t value) { bytes(&value, sizeof value); }
  void text(const std::string& value) {
    number(value.size());
    bytes(value.data(), value.size());
  }
  template <class T>
  void values(const std::vector<T>& vector) {
    number(vector.size());
    bytes(vector.data(), vector.size() * sizeof(T));
  }
  void diagnostic(const Diagnostic& d) {
    text(d.where.fileName());
    number(static_cast<std::uint64_t>(std::max(0, d.where.line)));
    number(static_cast<std::uint64_t>(std::max(0, d.where.column)));
    text(d.message);
  }
  std::string take() { return std::move(out_); }

 private:
  void bytes(const void* data, std::size_t size) {
    out_.append(static_cast<const char*>(data), size);
  }
  std::string out_;
};

class AnswerReader {
 public:
  explicit AnswerReader(const std::string& in) : in_(in) {}

  bool number(std::uint64_t& value) { return bytes(&value, sizeof value); }
  bool text(std::string& value) {
    std::uint64_t size = 0;
    if (!number(size) || size > left() || size > (1u << 20)) return false;
    value.assign(in_.data() + at_, size);
    at_ += size;
    return true;
  }
  template <class T>
  bool values(std::vector<T>& vector) {
    std::uint64_t count = 0;
    if (!number(count) || count > left() / sizeof(T)) return false;
    vector.resize(count);
    return bytes(vector.data(), count * sizeof(T));
  }
  bool diagnostic(Diagnostic& d) {
    std::string file;
    std::uint64_t line = 0, column = 0;
    if (!text(file) || !number(line) || !number(column) || !text(d.message)) return false;
    if (line > 1u << 30 || column > 1u << 30) return false;
    d.where = SourceLocation{std::make_shared<const std::string>(file), static_cast<int>(line),
                             static_cast<int>(column)};
    return true;
  }
  bool atEnd() const { return at_ == in_.size(); }

 private:
  std::size_t left() const { return in_.size() - at_; }
  bool bytes(void* data, std::size_t size) {
    if (size > left()) return false;
    if (size > 0) std::memcpy(data, in_.data() + at_, size);
    at_ += size;
    return true;
  }
  const std::string& in_;
  std::size_t at_ = 0;
};

std::string meshAnswer(const SurfaceMeshData& data, const std::vector<Diagnostic>& warnings) {
  AnswerWriter out;
  out.number(kAnswerMesh);
  out.number(warnings.size());
  for (const Diagnostic& warning : warnings) out.diagnostic(warning);
  out.values(data.positions);
  out.values(data.normals);
  out.values(data.uv);
  out.values(data.colours);
  out.values(data.indices);
  out.number(data.fileUvs ? 1 : 0);
  out.number(static_cast<std::uint64_t>(data.uvSource));
  out.values(std::vector<glm::dvec3>{data.boundsMin, data.boundsMax});
  out.number(data.laterPositions.size());
  for (std::size_t k = 0; k < data.laterPositions.size(); ++k) {
    out.values(data.laterPositions[k]);
    out.values(data.laterNormals[k]);
  }
  out.values(data.atlasUv);
  out.values(data.atlasChart);
  return out.take();
}

std::string errorAnswer(const Diagnostic& error, const std::vector<Diagnostic>& warnings) {
  AnswerWriter out;
  out.number(kAnswerError);
  out.number(warnings.size());
  for (const Diagnostic& warning : warnings) out.diagnostic(warning);
  out.diagnostic(error);
  return out.take();
}

// The child's answer: the mesh, after its warnings are passed on, or its error thrown. False
// when the answer is not one the child's code could have sent.
bool readAnswer(const std::string& answer, SurfaceMeshData& data, Diagnostics& diagnostics) {
  AnswerReader in(answer);
  std::uint64_t kind = 0, count = 0;
  if (!in.number(kind) || !in.number(count) || count > answer.size()) return false;
  std::vector<Diagnostic> warnings(count);
  for (Diagnostic& warning : warnings) {
    if (!in.diagnostic(warning)) return false;
  }
  if (kind == kAnswerError) {
    Diagnostic error;
    if (!in.diagnostic(error) || !in.atEnd()) return false;
    for (const Diagnostic& warning : warnings) diagnostics.warn(warning.where, warning.message);
    throw DiagnosticError(error.where, error.message);
  }
  std::uint64_t fileUvs = 0, uvSource = 0, frames = 0;
  std::vector<glm::dvec3> bounds;
  if (kind != kAnswerMesh || !in.values(data.positions) || !in.values(data.normals) ||
      !in.values(data.uv) || !in.values(data.colours) || !in.values(data.indices) ||
      !in.number(fileUvs) || !in.number(uvSource) || !in.values(bounds) || !in.number(frames) ||
      fileUvs > 1 || uvSource > static_cast<std::uint64_t>(MeshUvSource::Planar) ||
      bounds.size() != 2 || frames > answer.size()) {
    return false;
  }
  data.fileUvs = fileUvs == 1;
  data.uvSource = static_cast<MeshUvSource>(uvSource);
  data.boundsMin = bounds[0];
  data.boundsMax = bounds[1];
  const std::size_t vertices = data.positions.size();
  data.laterPositions.resize(frames);
  data.laterNormals.resize(frames);
  for (std::size_t k = 0; k < frames; ++k) {
    if (!in.values(data.laterPositions[k]) || !in.values(data.laterNormals[k]) ||
        data.laterPositions[k].size() != vertices || data.laterNormals[k].size() != vertices) {
      return false;
    }
  }
  if (!in.values(data.atlasUv) || !in.values(data.atlasChart)) return false;
  // What the rest of the program relies on: one of each per vertex, indices naming vertices, an
  // atlas (u, v) per corner and chart per triangle, or none.
  if (!data.atlasUv.empty() && (data.atlasUv.size() != data.indices.size() ||
                                data.atlasChart.size() != data.indices.size() / 3)) {
    return false;
  }
  if (!in.atEnd() || data.normals.size() != vertices || data.uv.size() != vertices ||
      (!data.colours.empty() && data.colours.size() != vertices) || data.indices.size() % 3 != 0 ||
      std::any_of(data.indices.begin(), data.indices.end(),
                  [&](std::uint32_t i) { return i >= vertices; })) {
    return false;
  }
  for (const Diagnostic& warning : warnings) diagnostics.warn(warning.where, warning.message);
  return true;
}

// What the child may spend on one file (docs/meshes.md, "Bad meshes"): a base, and more for
// each triangle the limit allows and each byte of the file.
constexpr std::size_t kReaderBaseBytes = std::size_t(1) << 30;
constexpr std::size_t kReaderBytesPerTriangle = 1024;
constexpr std::size_t kReaderBytesPerFileByte = 4;
constexpr double kReaderBaseSeconds = 15;
constexpr double kReaderSecondsPerMillionTriangles = 5;
constexpr double kReaderSecondsPerMegabyte = 1;

std::size_t saturated(std::size_t a, std::size_t b, std::size_t factor) {
  if (factor != 0 && b > (std::numeric_limits<std::size_t>::max() - a) / factor) {
    return std::numeric_limits<std::size_t>::max() / 2;
  }
  return a + b * factor;
}

SurfaceMeshData readMeshFileInChild(const fs::path& file, const fs::path& folder,
                                    std::size_t maxTriangles, Diagnostics& diagnostics) {
  std::error_code error;
  const std::uintmax_t fileBytes = fs::file_size(file, error);
  const std::size_t bytes = error ? 0 : static_cast<std::size_t>(fileBytes);
  IsolatedCallLimits limits;
  limits.memoryBytes = saturated(saturated(kReaderBaseBytes, maxTriangles, kReaderBytesPerTriangle),
                                 bytes, kReaderBytesPerFileByte);
  const double seconds =
      kReaderBaseSeconds +
      kReaderSecondsPerMillionTriangles * static_cast<double>(maxTriangles) / 1e6 +
      kReaderSecondsPerMegabyte * static_cast<double>(bytes) / 1e6;
  limits.time =
      std::chrono::milliseconds(static_cast<long long>(std::min(seconds, 86400.0) * 1000));
  limits.readableFolder = folder.empty() ? fs::path(".") : folder;
  limits.maxOutputBytes = limits.memoryBytes;

  IsolatedCallResult result;
  try {
    result = callIsolated(
        [&]() -> std::string {
          Diagnostics local;
          try {
            const SurfaceMeshData data = readMeshFile(file, folder, maxTriangles, local);
            return meshAnswer(data, local.warnings());
          } catch (const DiagnosticError& e) {
            return errorAnswer(e.diagnostic(), local.warnings());
          }
        },
        limits);
  } catch (const std::system_error& e) {
    throw DiagnosticError(at(file), fmt::format("cannot start the mesh reader: {}", e.what()));
  }
  using End = IsolatedCallResult::End;
  switch (result.end) {
    case End::Finished: {
      SurfaceMeshData data;
      if (readAnswer(result.output, data, diagnostics)) return data;
      throw DiagnosticError(at(file), "the mesh reader sent back a broken answer");
    }
    case End::TimedOut:
      throw DiagnosticError(
          at(file), fmt::format("reading the mesh took more than {:.0f} s, the limit for this file "
                                "(Assimp is stuck on it: the file is malformed); it was stopped",
                                seconds));
    case End::OutOfMemory:
      throw DiagnosticError(
          at(file), fmt::format("reading the mesh needed more than {} MB of memory, the limit for "
                                "this file (it grows with --max-mesh-triangles)",
                                limits.memoryBytes >> 20));
    case End::Crashed:
      throw DiagnosticError(at(file), fmt::format("the mesh reader (Assimp) crashed on this file "
                                                  "with {}: the file is malformed",
                                                  signalDescription(result.signal)));
    case End::Failed:
      break;
  }
  throw DiagnosticError(at(file), "the mesh reader failed: " + result.why);
}

}  // namespace

bool isMeshFile(const fs::path& file) {
  const std::string extension = lowerExtension(file);
  if (extension.empty() || extension == ".s") return false;
  static const Assimp::Importer importer;
  return importer.IsExtensionSupported(extension);
}

SurfaceMeshData loadMeshFile(const fs::path& file, const fs::path& folder, std::size_t maxTriangles,
                             Diagnostics& diagnostics, MeshReading reading) {
  if (reading == MeshReading::InProcess)
    return readMeshFile(file, folder, maxTriangles, diagnostics);
  return readMeshFileInChild(file, folder, maxTriangles, diagnostics);
}

SurfaceMeshData loadMeshSequence(const fs::path& pattern, const fs::path& folder,
                                 std::size_t maxTriangles, Diagnostics& diagnostics,
                                 MeshReading reading) {
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
  SurfaceMeshData data =
      loadMeshFile(frameFile(numbers.front()), folder, maxTriangles, diagnostics, reading);
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
    SurfaceMeshData frame =
        loadMeshFile(frameFile(numbers[k]), folder, maxTriangles, quiet, reading);
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
