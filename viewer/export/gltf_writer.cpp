#include "hirsute/viewer/export/gltf_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "hirsute/core/loadable_module.h"
#include "hirsute/viewer/export/export_file.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

// glTF's colours are linear (glTF 2.0, section 3.9.2); ours are display (sRGB) values, as the
// screen shows them and as the OBJ's .mtl writes them.
float srgbToLinear(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 srgbToLinear(const glm::vec3& c) {
  return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)};
}

void requireFinite(const glm::vec3& v) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw std::invalid_argument("a coordinate is not a finite number");
}

// The glTF module's functions; throws std::runtime_error naming `target` when it cannot be loaded.
const GltfFunctions& gltfModule(const fs::path& target) {
  static std::once_flag loaded;
  static const GltfFunctions* functions = nullptr;
  static std::string error;
  std::call_once(loaded, [] {
    using Entry = const GltfFunctions* (*)();
    if (void* entry =
            moduleEntry("libhirsute-gltf.so", "HIRSUTE_GLTF_MODULE", "hirsuteGltfFunctions", error))
      functions = reinterpret_cast<Entry>(entry)();
  });
  if (functions == nullptr) {
    // Not the model's fault: an error of the installation (exit code 1), not a diagnostic.
    throw std::runtime_error("cannot write the glTF " + target.string() + ": " + error +
                             " (glTF needs the glTF module and Assimp; "
                             "scripts/install-deps.sh installs them)");
  }
  return *functions;
}

}  // namespace

bool gltfIsBinary(const fs::path& target) {
  std::string extension = target.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".glb") return true;
  if (extension == ".gltf") return false;
  throw std::invalid_argument(target.string() + ": a glTF file's name ends in .gltf or .glb");
}

fs::path gltfBufferFile(const fs::path& target) {
  return fs::path(target).replace_extension(".bin");
}

GltfWriter::GltfWriter(fs::path target, GltfOptions options)
    : target_(std::move(target)), options_(std::move(options)) {
  gltfIsBinary(target_);
}

void GltfWriter::beginScene(const Scene& scene, std::span<const OrganWriter* const>) {
  scene_ = &scene;
  const Camera c =
      fitCamera(options_.view, scene.bounds(), glm::ivec2(options_.width, options_.height));
  GltfCamera& camera = gltf_.camera;
  // A parallel camera's near plane may lie behind its eye (the plant is fitted around the point
  // looked at); glTF's clipping starts at the camera, so it stands on the near plane, as the
  // scene for Blender's does.
  camera.perspective = c.projection == Projection::Perspective;
  camera.location = camera.perspective ? c.eye : c.eye + c.forward * c.nearPlane;
  camera.forward = c.forward;
  camera.up = c.up;
  camera.fieldOfViewY = glm::radians(c.fieldOfViewY);
  camera.halfWidth = c.halfWidth;
  camera.halfHeight = c.halfHeight;
  camera.aspect = static_cast<float>(options_.width) / static_cast<float>(options_.height);
  camera.clipStart = camera.perspective ? c.nearPlane : 0.0f;
  camera.clipEnd = camera.perspective ? c.farPlane : std::max(c.farPlane - c.nearPlane, 1e-3f);
  requireFinite(camera.location);
}

int GltfWriter::material(int sceneMaterial) {
  if (const auto known = materials_.find(sceneMaterial); known != materials_.end())
    return known->second;
  static const Material kDefault{};
  const bool inPalette =
      sceneMaterial >= 0 && static_cast<std::size_t>(sceneMaterial) < scene_->materials.size();
  const Material& m =
      inPalette ? scene_->materials[static_cast<std::size_t>(sceneMaterial)] : kDefault;
  GltfMaterial entry;
  entry.name = fmt::format("{}{}", sceneMaterial < 0 ? "mn" : "m", std::abs(sceneMaterial));
  entry.baseColour =
      glm::vec4(srgbToLinear(m.diffuse), 1.0f - std::clamp(m.transparency, 0.0f, 1.0f));
  entry.emission = srgbToLinear(m.emission);
  gltf_.materials.push_back(std::move(entry));
  const int index = static_cast<int>(gltf_.materials.size() - 1);
  materials_.emplace(sceneMaterial, index);
  return index;
}

void GltfWriter::addMesh(int sceneMaterial, std::vector<glm::vec3> positions,
                         std::vector<glm::vec3> normals, std::vector<std::uint32_t> indices) {
  for (const glm::vec3& p : positions) requireFinite(p);
  GltfMesh out;
  out.name = fmt::format("mesh{}", gltf_.meshes.size());
  out.material = material(sceneMaterial);
  stats_.vertices += positions.size();
  stats_.triangles += indices.size() / 3;
  out.positions = std::move(positions);
  out.normals = std::move(normals);
  out.indices = std::move(indices);
  gltf_.meshes.push_back(std::move(out));
}

void GltfWriter::mesh(const TriangleMesh& mesh) {
  const std::size_t count = mesh.positions.size();
  if (count == 0 || mesh.indices.size() < 3) return;
  for (std::uint32_t index : mesh.indices) {
    if (index >= count)
      throw std::invalid_argument("a mesh's triangle refers to a vertex it does not have");
  }
  std::vector<glm::vec3> normals;
  if (mesh.normals.size() == count) {
    VertexNormals unit(mesh);
    normals.reserve(count);
    for (std::size_t i = 0; i < count; ++i) normals.push_back(unit[i]);
  }
  addMesh(mesh.material, mesh.positions, std::move(normals),
          std::vector<std::uint32_t>(
              mesh.indices.begin(),
              mesh.indices.begin() + static_cast<std::ptrdiff_t>(mesh.triangleCount() * 3)));
}

void GltfWriter::sphere(const Sphere& sphere) {
  appendSphere(spheres_[sphere.material], sphere.center, sphere.radius);
}

void GltfWriter::disc(const Disc& disc) {
  // A screen-aligned disc (cpfg's @o) faces the camera.
  const glm::vec3 n =
      glm::length(disc.normal) > 0 ? glm::normalize(disc.normal) : -gltf_.camera.forward;
  appendDisc(discs_[disc.material], disc.center, disc.radius, n);
}

void GltfWriter::endScene() {
  // The spheres and discs, one mesh a material each, after the scene's meshes.
  for (auto* gathered : {&spheres_, &discs_}) {
    for (auto& [sceneMaterial, g] : *gathered)
      addMesh(sceneMaterial, std::move(g.positions), std::move(g.normals), std::move(g.indices));
    gathered->clear();
  }
  const bool binary = gltfIsBinary(target_);
  const fs::path buffer = gltfBufferFile(target_);
  const GltfBytes bytes = gltfModule(target_).encode(gltf_, binary, buffer.filename().string());
  if (!bytes.error.empty())
    throw std::runtime_error(target_.string() + ": cannot write the glTF: " + bytes.error);
  ExportFile file(target_, options_.group);
  file.putBytes(bytes.file.data(), bytes.file.size());
  file.commit();
  stats_.bytes = bytes.file.size();
  if (!binary && !bytes.buffer.empty()) {
    // A name derived from the typed one: created beside it without following a link planted at
    // the name (output_folder.h).
    const fs::path folder = buffer.has_parent_path() ? buffer.parent_path() : fs::path(".");
    ExportFile side(OutputFolder(folder), buffer.filename().string(), options_.group);
    side.putBytes(bytes.buffer.data(), bytes.buffer.size());
    side.commit();
    stats_.bytes += bytes.buffer.size();
  }
  stats_.meshes = gltf_.meshes.size();
  stats_.materials = gltf_.materials.size();
}

GltfExportStats writeGltf(const Scene& scene, const GltfOptions& options, const fs::path& target,
                          Progress* progress) {
  GltfWriter writer(target, options);
  printScene(scene, writer, progress, "writing glTF");
  return writer.stats();
}

}  // namespace hirsute
