#include "hirsute/viewer/export/obj_writer.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <stdexcept>

#include "hirsute/viewer/export/texture_file.h"
#include "hirsute/viewer/view/view_lighting.h"

namespace hirsute {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string materialName(int material, int texture) {
  std::string name(material < 0 ? "mn" : "m");
  name += std::to_string(material < 0 ? -static_cast<long>(material) : material);
  if (texture >= 0) {
    name += "_t";
    name += std::to_string(texture + 1);
  }
  return name;
}

// A UV sphere of radius 1: a point at each pole and stacks - 1 rings of `slices` points between.
void unitSphere(int slices, int stacks, std::vector<glm::vec3>& points,
                std::vector<std::uint32_t>& triangles) {
  slices = std::max(slices, 3);
  stacks = std::max(stacks, 2);
  points.push_back({0, 1, 0});
  for (int i = 1; i < stacks; ++i) {
    double polar = kPi * i / stacks;
    for (int j = 0; j < slices; ++j) {
      double azimuth = 2 * kPi * j / slices;
      points.push_back(glm::vec3(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                                 -std::sin(polar) * std::sin(azimuth)));
    }
  }
  points.push_back({0, -1, 0});
  auto ring = [slices](int i, int j) {
    return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices));
  };
  auto bottom = static_cast<std::uint32_t>(points.size() - 1);
  for (int j = 0; j < slices; ++j) {
    triangles.insert(triangles.end(), {0u, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < stacks; ++i) {
      triangles.insert(triangles.end(), {ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      triangles.insert(triangles.end(), {ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
    triangles.insert(triangles.end(), {ring(stacks - 1, j), bottom, ring(stacks - 1, j + 1)});
  }
}

}  // namespace

ObjWriter::ObjWriter(std::filesystem::path target, ObjOptions options)
    : target_(std::move(target)),
      mtlName_(std::filesystem::path(target_.filename()).replace_extension(".mtl").string()),
      options_(options),
      out_(options_.folder
               ? ExportFile(*options_.folder, target_.filename().string(), options_.group)
               : ExportFile(target_, options_.group)) {
  if (mtlName_ == target_.filename())
    throw std::invalid_argument(target_.string() + ": the OBJ file cannot end in .mtl");
  unitSphere(options_.sphereSlices, options_.sphereStacks, spherePoints_, sphereTriangles_);
}

ObjWriter::~ObjWriter() = default;

void ObjWriter::beginScene(const Scene& scene, std::span<const OrganWriter* const>) {
  scene_ = &scene;
  position_.decimals = positionDecimals(scene.bounds());
  out_.put("# Hirsute: ");
  out_.putInteger(static_cast<std::int64_t>(scene.triangleCount()));
  out_.put(" triangles and ");
  out_.putInteger(static_cast<std::int64_t>(scene.lines.size()));
  out_.put(" line segments (docs/export.md)\n");
  // Written to a device or FIFO, the OBJ has no folder for its material library and images: it
  // names none, and they are not written (no side file beside /dev/null).
  if (!out_.writesInPlace()) {
    out_.put("mtllib ");
    out_.put(mtlName_);
    out_.put('\n');
  }
}

void ObjWriter::group(std::string_view name) {
  if (currentGroup_ == name || options_.oneObject) return;
  out_.put("o ");
  out_.put(name);
  out_.put('\n');
  currentGroup_ = name;
}

void ObjWriter::useMaterial(int material, int texture) {
  std::pair<int, int> key{material, texture};
  if (key == current_) return;
  if (materialSet_.insert(key).second) {
    materialsUsed_.push_back(key);
    writeTextureOnce(texture);
  }
  out_.put("usemtl ");
  out_.put(materialName(material, texture));
  out_.put('\n');
  current_ = key;
}

// The texture's image beside the OBJ, once however many materials use it (none in place: a
// device or FIFO has no folder beside it).
void ObjWriter::writeTextureOnce(int texture) {
  if (texture < 0 || out_.writesInPlace() || !texturesWritten_.insert(texture).second) return;
  writeTexturePng(scene_->textures.at(static_cast<std::size_t>(texture)), sideFolder(),
                  textureFileName(target_, texture), options_.group);
}

const OutputFolder& ObjWriter::sideFolder() {
  if (options_.folder) return *options_.folder;
  if (!sideFolder_) sideFolder_.emplace(target_.parent_path());
  return *sideFolder_;
}

void ObjWriter::useOrganMaterial(const std::string& name, const glm::vec3& diffuse, int texture) {
  if (current_ == std::pair<int, int>{-1, -1} && currentOrganMaterial_ == name) return;
  const auto known = std::find_if(organMaterials_.begin(), organMaterials_.end(),
                                  [&](const OrganMaterial& m) { return m.name == name; });
  if (known == organMaterials_.end()) {
    organMaterials_.push_back({name, diffuse, texture});
    writeTextureOnce(texture);
  }
  out_.put("usemtl ");
  out_.put(name);
  out_.put('\n');
  current_ = {-1, -1};  // the next useMaterial writes its usemtl again
  currentOrganMaterial_ = name;
}

void ObjWriter::texcoord(const glm::vec2& t) {
  out_.put("vt ");
  out_.putFixed(t.x, texcoord_);
  out_.put(' ');
  out_.putFixed(t.y, texcoord_);
  out_.put('\n');
  ++stats_.texcoords;
}

void ObjWriter::putVertexPosition(const glm::vec3& p) {
  if (options_.positions != nullptr) options_.positions->push_back(p);
  out_.put("v ");
  out_.putFixed(p.x, position_);
  out_.put(' ');
  out_.putFixed(p.y, position_);
  out_.put(' ');
  out_.putFixed(p.z, position_);
}

void ObjWriter::vertex(const glm::vec3& p) {
  putVertexPosition(p);
  out_.put('\n');
  ++stats_.vertices;
}

void ObjWriter::vertex(const glm::vec3& p, const glm::vec3& colour) {
  putVertexPosition(p);
  for (int k = 0; k < 3; ++k) {
    out_.put(' ');
    out_.putFixed(std::clamp(colour[k], 0.0f, 1.0f), NumberFormat{4, true});
  }
  out_.put('\n');
  ++stats_.vertices;
}

void ObjWriter::normal(const glm::vec3& n) {
  out_.put("vn ");
  out_.putFixed(n.x, normal_);
  out_.put(' ');
  out_.putFixed(n.y, normal_);
  out_.put(' ');
  out_.putFixed(n.z, normal_);
  out_.put('\n');
  ++stats_.normals;
}

void ObjWriter::mesh(const TriangleMesh& mesh) {
  finishPolyline();
  std::size_t count = mesh.positions.size();
  for (std::uint32_t index : mesh.indices) {
    if (index >= count)
      throw std::invalid_argument("a mesh's triangle refers to a vertex it does not have");
  }
  bool normals = mesh.normals.size() == count;
  bool textured = drawnTextured(*scene_, mesh);
  // OBJ numbers vertices, normals and texture coordinates from 1 across the whole file.
  std::uint64_t firstVertex = stats_.vertices + 1, firstNormal = stats_.normals + 1,
                firstTexcoord = stats_.texcoords + 1;
  if (!options_.oneObject) {
    out_.put("o mesh");
    out_.putInteger(meshNumber_);
    out_.put('\n');
  }
  ++meshNumber_;
  currentGroup_ = {};
  useMaterial(mesh.material, textured ? mesh.texture : -1);
  for (const glm::vec3& p : mesh.positions) vertex(p);
  if (normals) {
    VertexNormals unit(mesh);
    for (std::size_t i = 0; i < count; ++i) normal(unit[i]);
  }
  if (textured) {
    // t = 0 is the image's bottom row, in OBJ as in the GL renderer.
    for (const glm::vec2& t : mesh.texcoords) texcoord(t);
  }
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    out_.put('f');
    for (int k = 0; k < 3; ++k) {
      std::uint32_t index = mesh.indices[t + static_cast<std::size_t>(k)];
      out_.put(' ');
      out_.putInteger(static_cast<std::int64_t>(firstVertex + index));
      if (textured || normals) {
        out_.put('/');
        if (textured) out_.putInteger(static_cast<std::int64_t>(firstTexcoord + index));
        if (normals) {
          out_.put('/');
          out_.putInteger(static_cast<std::int64_t>(firstNormal + index));
        }
      }
    }
    out_.put('\n');
    ++stats_.faces;
  }
}

void ObjWriter::line(const LineSegment& line, LineStyle) {
  // Consecutive segments that continue each other in one material become one polyline; OBJ
  // has no line width, so widths are not kept.
  bool continues = !polyline_.empty() && current_ == std::pair<int, int>(line.material, -1) &&
                   line.from == polylineEnd_;
  if (!continues) {
    finishPolyline();
    group("lines");
    useMaterial(line.material, -1);
    vertex(line.from);
    polyline_.push_back(stats_.vertices);
  }
  vertex(line.to);
  polyline_.push_back(stats_.vertices);
  polylineEnd_ = line.to;
}

// Each segment of the polyline is an `l` element of its two vertices, consecutive segments
// sharing their vertex: Blender's default OBJ importer (3.4's, in C++) keeps only the first
// segment of a longer `l` element and misreads `l v/vt`, its legacy importer reads both forms,
// and a reader that joins `l` elements into polylines finds the chain. Edges have no texture
// coordinates in either importer, so none are written.
void ObjWriter::finishPolyline() {
  for (std::size_t i = 0; i + 1 < polyline_.size(); ++i) {
    out_.put("l ");
    out_.putInteger(static_cast<std::int64_t>(polyline_[i]));
    out_.put(' ');
    out_.putInteger(static_cast<std::int64_t>(polyline_[i + 1]));
    out_.put('\n');
    ++stats_.lineElements;
  }
  if (polyline_.size() > 1) ++stats_.polylines;
  polyline_.clear();
}

void ObjWriter::sphere(const Sphere& sphere) {
  finishPolyline();
  group("spheres");
  useMaterial(sphere.material, -1);
  std::uint64_t firstVertex = stats_.vertices + 1, firstNormal = stats_.normals + 1;
  for (const glm::vec3& p : spherePoints_) vertex(sphere.center + p * sphere.radius);
  for (const glm::vec3& p : spherePoints_) normal(p);
  for (std::size_t t = 0; t < sphereTriangles_.size(); t += 3) {
    out_.put('f');
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t index = sphereTriangles_[t + k];
      out_.put(' ');
      out_.putInteger(static_cast<std::int64_t>(firstVertex + index));
      out_.put("//");
      out_.putInteger(static_cast<std::int64_t>(firstNormal + index));
    }
    out_.put('\n');
    ++stats_.faces;
  }
}

void ObjWriter::disc(const Disc& disc) {
  finishPolyline();
  group("discs");
  useMaterial(disc.material, -1);
  // A screen-aligned disc (cpfg's @o) has no direction of its own; OBJ has no camera, so it
  // faces +z, towards cpfg's default viewpoint.
  glm::vec3 n = glm::length(disc.normal) > 0 ? glm::normalize(disc.normal) : glm::vec3(0, 0, 1);
  glm::vec3 helper = std::fabs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  glm::vec3 u = glm::normalize(glm::cross(n, helper));
  glm::vec3 v = glm::cross(n, u);
  int segments = std::max(options_.discSegments, 3);
  std::uint64_t centre = stats_.vertices + 1;
  vertex(disc.center);
  for (int i = 0; i < segments; ++i) {
    double angle = 2 * kPi * i / segments;
    vertex(disc.center + disc.radius * (static_cast<float>(std::cos(angle)) * u +
                                        static_cast<float>(std::sin(angle)) * v));
  }
  normal(n);
  std::uint64_t normalIndex = stats_.normals;
  for (int i = 0; i < segments; ++i) {
    std::uint64_t corners[3] = {centre, centre + 1 + static_cast<std::uint64_t>(i),
                                centre + 1 + static_cast<std::uint64_t>((i + 1) % segments)};
    out_.put('f');
    for (std::uint64_t corner : corners) {
      out_.put(' ');
      out_.putInteger(static_cast<std::int64_t>(corner));
      out_.put("//");
      out_.putInteger(static_cast<std::int64_t>(normalIndex));
    }
    out_.put('\n');
    ++stats_.faces;
  }
}

void ObjWriter::label(const Label& label) {
  // OBJ has no text; the label stays as a comment.
  finishPolyline();
  out_.put("# label \"");
  for (char c : label.text) out_.put(c == '\n' || c == '\r' ? ' ' : c);
  out_.put("\" at ");
  out_.putFixed(label.position.x, position_);
  out_.put(' ');
  out_.putFixed(label.position.y, position_);
  out_.put(' ');
  out_.putFixed(label.position.z, position_);
  out_.put('\n');
}

void ObjWriter::writeMaterialLibrary() {
  ExportFile mtl(sideFolder(), mtlName_, options_.group);
  NumberFormat colour{4, true};
  auto rgb = [&mtl, colour](const char* key, const glm::vec3& c) {
    mtl.put(key);
    for (int i = 0; i < 3; ++i) {
      mtl.put(' ');
      mtl.putFixed(std::clamp(c[i], 0.0f, 1.0f), colour);
    }
    mtl.put('\n');
  };
  mtl.put("# Hirsute: the materials of ");
  mtl.put(target_.filename().string());
  mtl.put('\n');
  for (const auto& [index, texture] : materialsUsed_) {
    const Material& m = materialOrDefault(*scene_, index);
    mtl.put("newmtl ");
    mtl.put(materialName(index, texture));
    mtl.put('\n');
    rgb("Ka", m.ambient);
    rgb("Kd", m.diffuse);
    rgb("Ks", m.specular);
    if (m.emission != glm::vec3(0.0f)) rgb("Ke", m.emission);
    // Ns is the Phong exponent, as GL's shininess is.
    mtl.put("Ns ");
    mtl.putFixed(std::clamp(m.shininess, 0.0f, 1000.0f), colour);
    mtl.put("\nd ");
    mtl.putFixed(1.0f - std::clamp(m.transparency, 0.0f, 1.0f), colour);
    mtl.put("\nillum 2\n");
    if (texture >= 0) {
      mtl.put("map_Kd ");
      mtl.put(textureFileName(target_, texture));
      mtl.put('\n');
    }
  }
  for (const OrganMaterial& m : organMaterials_) {
    mtl.put("newmtl ");
    mtl.put(m.name);
    mtl.put('\n');
    rgb("Kd", m.diffuse);
    mtl.put("illum 1\n");
    if (m.texture >= 0) {
      mtl.put("map_Kd ");
      mtl.put(textureFileName(target_, m.texture));
      mtl.put('\n');
    }
  }
  mtl.commit();
  stats_.mtlBytes = mtl.bytesWritten();
  stats_.materials = materialsUsed_.size() + organMaterials_.size();
}

void ObjWriter::endScene() {
  finishPolyline();
  // The library first, so that the OBJ never appears naming a library that is not there.
  if (!out_.writesInPlace()) writeMaterialLibrary();
  out_.commit();
  stats_.bytes = out_.bytesWritten();
}

void ObjWriter::organ(const OrganWriter& organ, const Scene& scene) {
  finishPolyline();
  organ.writeObj(scene, *this);
}

void ObjWriter::face(const std::array<std::uint64_t, 3>& vertices,
                     const std::optional<std::array<std::uint64_t, 3>>& normals,
                     const std::optional<std::array<std::uint64_t, 3>>& texcoords) {
  out_.put('f');
  for (std::size_t k = 0; k < 3; ++k) {
    out_.put(' ');
    out_.putInteger(static_cast<std::int64_t>(vertices[k]));
    if (texcoords) {
      out_.put('/');
      out_.putInteger(static_cast<std::int64_t>((*texcoords)[k]));
    }
    if (normals) {
      out_.put(texcoords ? "/" : "//");
      out_.putInteger(static_cast<std::int64_t>((*normals)[k]));
    }
  }
  out_.put('\n');
  ++stats_.faces;
}

void ObjWriter::count(std::string_view what, std::uint64_t count) {
  const auto found = stats_.organs.find(what);
  if (found != stats_.organs.end()) {
    found->second += count;
  } else {
    stats_.organs.emplace(std::string(what), count);
  }
}

}  // namespace hirsute
