#include "hirsute/viewer/export/blender_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "hirsute/viewer/export/primitive_mesh.h"
#include "hirsute/viewer/view/view_lighting.h"

namespace hirsute {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the Blender file's arrays are little-endian, written as the machine holds them");

// GL's default global ambient light (glLightModel GL_LIGHT_MODEL_AMBIENT), which cpfg leaves as is.
constexpr float kGlobalAmbient = 0.2f;
constexpr std::size_t kFooterBytes = 24;  // index offset, index length, magic

// Blender's colours are linear; ours are display (sRGB) values, as the screen shows them.
float srgbToLinear(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 srgbToLinear(const glm::vec3& c) {
  return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)};
}

void requireFinite(float value) {
  if (!std::isfinite(value)) throw std::invalid_argument("a coordinate is not a finite number");
}

std::string number(double value) {
  if (!std::isfinite(value)) throw std::invalid_argument("a value is not a finite number");
  return fmt::format("{}", static_cast<float>(value));
}

std::string vec(const glm::vec3& v) {
  return "[" + number(v.x) + "," + number(v.y) + "," + number(v.z) + "]";
}

// A JSON string of any bytes: quotes, backslashes and control bytes escaped, bytes above 127
// as the Latin-1 characters of their value (a file name need not be UTF-8).
std::string jsonString(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte > 0x7e) {
      out += fmt::format("\\u{:04x}", byte);
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string offset(std::uint64_t value, bool present) {
  return present ? std::to_string(value) : "null";
}

}  // namespace

BlenderWriter::BlenderWriter(std::filesystem::path target, BlenderOptions options)
    : target_(std::move(target)), options_(std::move(options)), out_(target_, options_.group) {}

BlenderWriter::~BlenderWriter() = default;

std::uint64_t BlenderWriter::put(const void* data, std::size_t bytes) {
  const std::uint64_t at = out_.bytesWritten();
  out_.putBytes(data, bytes);
  return at;
}

void BlenderWriter::beginScene(const Scene& scene, std::span<const OrganWriter* const>) {
  scene_ = &scene;
  const Bounds bounds = scene.bounds();
  camera_ = fitCamera(options_.view, bounds, glm::ivec2(options_.width, options_.height));
  const float pixels = static_cast<float>(camera_.viewport.y);
  worldPerPixel_ = camera_.projection == Projection::Perspective
                       ? 2 * glm::distance(camera_.eye, camera_.target) *
                             std::tan(glm::radians(camera_.fieldOfViewY) / 2) / pixels
                       : 2 * camera_.halfHeight / pixels;
  out_.put(std::string_view(kBlenderMagic, 8));
  const std::uint32_t head[2] = {kBlenderVersion, 0};
  out_.putBytes(head, sizeof head);
}

int BlenderWriter::sceneMaterial(int material, Shading shading) {
  const std::pair<int, int> key{material, static_cast<int>(shading)};
  if (const auto known = sceneMaterials_.find(key); known != sceneMaterials_.end())
    return known->second;
  const Material& m = materialOrDefault(*scene_, material);
  std::string name = fmt::format("{}{}", material < 0 ? "mn" : "m", std::abs(material));
  if (shading == Shading::Hair) name += "_hair";
  materials_.push_back({name, m.diffuse, m.specular, m.emission, m.shininess,
                        1.0f - std::clamp(m.transparency, 0.0f, 1.0f), shading});
  const int entry = static_cast<int>(materials_.size() - 1);
  sceneMaterials_.emplace(key, entry);
  return entry;
}

int BlenderWriter::organMaterial(const std::string& name, const glm::vec3& diffuse,
                                 Shading shading) {
  if (const auto known = organMaterials_.find(name); known != organMaterials_.end())
    return known->second;
  materials_.push_back({name, diffuse, glm::vec3(0.0f), glm::vec3(0.0f), 0.0f, 1.0f, shading});
  const int entry = static_cast<int>(materials_.size() - 1);
  organMaterials_.emplace(name, entry);
  return entry;
}

void BlenderWriter::beginCurves(std::string_view organ, std::string_view name, int material) {
  endCurves();
  inGroup_ = true;
  groupOrgan_ = organ;
  groupName_ = name;
  groupMaterial_ = material;
  groupOffset_ = out_.bytesWritten();
  groupPoints_ = 0;
  curve_.clear();
  groupSizes_.clear();
}

void BlenderWriter::curvePoint(const glm::vec3& p, float radius, const glm::vec3& colour) {
  const glm::vec3 linear = srgbToLinear(colour);
  const std::array<float, 7> record{p.x,      p.y,      p.z,     std::max(radius, 0.0f),
                                    linear.r, linear.g, linear.b};
  for (float v : record) requireFinite(v);
  curve_.push_back(record);
}

void BlenderWriter::endCurve() {
  // A curve of one point draws nothing: it is left out, and the sizes say where each ends.
  if (curve_.size() >= 2) {
    out_.putBytes(curve_.data(), curve_.size() * sizeof(curve_[0]));
    groupSizes_.push_back(static_cast<std::uint32_t>(curve_.size()));
    groupPoints_ += curve_.size();
  }
  curve_.clear();
}

void BlenderWriter::endCurves() {
  if (!inGroup_) return;
  endCurve();
  inGroup_ = false;
  if (groupSizes_.empty()) return;
  const std::uint64_t sizes = put(groupSizes_.data(), groupSizes_.size() * sizeof(std::uint32_t));
  curveEntries_ += fmt::format(
      "{}\n  {{\"organ\":{},\"name\":{},\"material\":{},\"curves\":{},\"points\":{},"
      "\"data\":{},\"sizes\":{}}}",
      curveEntries_.empty() ? "" : ",", jsonString(groupOrgan_), jsonString(groupName_),
      groupMaterial_, groupSizes_.size(), groupPoints_, groupOffset_, sizes);
  ++stats_.curveGroups;
  stats_.curves += groupSizes_.size();
  stats_.points += groupPoints_;
}

void BlenderWriter::triangles(std::string_view organ, std::string_view name, int material,
                              std::span<const glm::vec3> positions,
                              std::span<const glm::vec3> normals,
                              std::span<const glm::vec2> texcoords,
                              std::span<const glm::vec3> colours,
                              std::span<const std::uint32_t> indices) {
  endCurves();
  const std::size_t count = positions.size();
  if (count == 0 || indices.size() < 3) return;
  for (std::uint32_t index : indices) {
    if (index >= count)
      throw std::invalid_argument("a mesh's triangle refers to a vertex it does not have");
  }
  for (const glm::vec3& p : positions) {
    requireFinite(p.x);
    requireFinite(p.y);
    requireFinite(p.z);
  }
  const std::size_t triangleCount = indices.size() / 3;
  const std::uint64_t at = put(positions.data(), count * sizeof(glm::vec3));
  const bool withNormals = normals.size() == count;
  const bool withTexcoords = texcoords.size() == count;
  const bool withColours = colours.size() == count;
  std::uint64_t normalsAt = 0, texcoordsAt = 0, coloursAt = 0;
  if (withNormals) normalsAt = put(normals.data(), count * sizeof(glm::vec3));
  if (withTexcoords) texcoordsAt = put(texcoords.data(), count * sizeof(glm::vec2));
  if (withColours) {
    coloursAt = out_.bytesWritten();
    for (const glm::vec3& c : colours) {
      const glm::vec3 linear = srgbToLinear(c);
      out_.putBytes(&linear, sizeof linear);
    }
  }
  const std::uint64_t indicesAt = put(indices.data(), triangleCount * 3 * sizeof(std::uint32_t));
  meshEntries_ += fmt::format(
      "{}\n  {{\"organ\":{},\"name\":{},\"material\":{},\"vertices\":{},\"triangles\":{},"
      "\"positions\":{},\"normals\":{},\"texcoords\":{},\"colours\":{},\"indices\":{}}}",
      meshEntries_.empty() ? "" : ",", jsonString(organ), jsonString(name), material, count,
      triangleCount, at, offset(normalsAt, withNormals), offset(texcoordsAt, withTexcoords),
      offset(coloursAt, withColours), indicesAt);
  ++stats_.meshes;
  stats_.triangles += triangleCount;
}

void BlenderWriter::mesh(const TriangleMesh& mesh) {
  const std::size_t count = mesh.positions.size();
  std::vector<glm::vec3> normals;
  if (mesh.normals.size() == count) {
    VertexNormals unit(mesh);
    normals.reserve(count);
    for (std::size_t i = 0; i < count; ++i) normals.push_back(unit[i]);
  }
  const std::span<const glm::vec2> texcoords = mesh.texcoords.size() == count
                                                   ? std::span<const glm::vec2>(mesh.texcoords)
                                                   : std::span<const glm::vec2>();
  triangles("surfaces", fmt::format("mesh{}", stats_.meshes),
            sceneMaterial(mesh.material, Shading::Surface), mesh.positions, normals, texcoords, {},
            mesh.indices);
}

void BlenderWriter::line(const LineSegment& line, LineStyle style) {
  // Pixel-wide lines take the fitted picture's pixel; the others are world widths.
  const float scale = style == LineStyle::Pixel ? worldPerPixel_ : 1.0f;
  const glm::vec3 colour = materialOrDefault(*scene_, line.material).diffuse;
  const bool continues = inGroup_ && groupOrgan_ == "lines" && lineMaterial_ == line.material &&
                         !curve_.empty() && line.from == lineEnd_;
  if (!continues) {
    if (!(inGroup_ && groupOrgan_ == "lines" && lineMaterial_ == line.material)) {
      beginCurves("lines", fmt::format("m{}", line.material),
                  sceneMaterial(line.material, Shading::Hair));
      lineMaterial_ = line.material;
    }
    endCurve();
    curvePoint(line.from, 0.5f * scale * line.widthFrom, colour);
  }
  curvePoint(line.to, 0.5f * scale * line.widthTo, colour);
  lineEnd_ = line.to;
}

void BlenderWriter::sphere(const Sphere& sphere) {
  endCurves();
  appendSphere(spheres_[sphere.material], sphere.center, sphere.radius);
}

void BlenderWriter::disc(const Disc& disc) {
  endCurves();
  // A screen-aligned disc (cpfg's @o) faces the camera.
  const glm::vec3 n = glm::length(disc.normal) > 0 ? glm::normalize(disc.normal) : -camera_.forward;
  appendDisc(discs_[disc.material], disc.center, disc.radius, n);
}

void BlenderWriter::label(const Label&) {
  endCurves();
}

void BlenderWriter::flushPrimitives() {
  endCurves();
  for (auto* gathered : {&spheres_, &discs_}) {
    const char* name = gathered == &spheres_ ? "spheres" : "discs";
    for (const auto& [material, g] : *gathered) {
      triangles("surfaces", fmt::format("{}_m{}", name, material),
                sceneMaterial(material, Shading::Surface), g.positions, g.normals, {}, {},
                g.indices);
    }
    gathered->clear();
  }
}

void BlenderWriter::organ(const OrganWriter& organ, const Scene& scene) {
  flushPrimitives();
  organ.writeBlender(scene, *this);
  endCurves();
}

void BlenderWriter::count(std::string_view what, std::uint64_t count) {
  const auto found = stats_.organs.find(what);
  if (found != stats_.organs.end()) {
    found->second += count;
  } else {
    stats_.organs.emplace(std::string(what), count);
  }
}

void BlenderWriter::endScene() {
  flushPrimitives();
  const Camera& c = camera_;
  std::string json =
      fmt::format("{{\"format\":\"hirsute-blender\",\"version\":{},\"up\":\"y\",", kBlenderVersion);
  json += fmt::format("\n\"picture\":[{},{}],", options_.width, options_.height);
  // Where the camera stands and what it clips. A parallel camera's near plane may lie behind
  // its eye (the plant is fitted around the point looked at); Blender's clipping starts at the
  // camera, so it stands on the near plane, as POV-Ray's does.
  const bool perspective = c.projection == Projection::Perspective;
  const glm::vec3 location = perspective ? c.eye : c.eye + c.forward * c.nearPlane;
  const float clipStart = perspective ? c.nearPlane : 0.0f;
  const float clipEnd = perspective ? c.farPlane : std::max(c.farPlane - c.nearPlane, 1e-3f);
  json += fmt::format(
      "\n\"camera\":{{\"projection\":\"{}\",\"location\":{},\"forward\":{},\"up\":{},"
      "\"fov_y\":{},\"width\":{},\"height\":{},\"clip\":[{},{}]}},",
      perspective ? "perspective" : "orthographic", vec(location), vec(c.forward), vec(c.up),
      number(c.fieldOfViewY), number(2 * c.halfWidth), number(2 * c.halfHeight), number(clipStart),
      number(clipEnd));
  // cpfg takes the background from entry 0 of the palette: the colour of a colour map, the
  // emission of a material file.
  glm::vec3 background(0.0f);
  if (!scene_->materials.empty()) {
    background = options_.materialMode ? scene_->materials.front().emission
                                       : scene_->materials.front().diffuse;
  }
  json += "\n\"background\":" + vec(srgbToLinear(background)) + ",";
  const Bounds bounds = scene_->bounds();
  const glm::vec3 centre = bounds.empty() ? options_.view.viewReference : bounds.center();
  json += "\n\"centre\":" + vec(centre) + ",\"size\":" + number(bounds.diagonal()) + ",";
  const std::vector<LightSource> lights =
      exportedLights(options_.view, options_.materialMode, -camera_.forward);
  // GL adds each light's ambient times the material's ambient colour: their sum lights the
  // plant from everywhere (the importer's world, to rays other than the camera's).
  glm::vec3 ambient(kGlobalAmbient);
  for (const LightSource& light : lights) ambient += light.ambient;
  json += "\n\"ambient\":" + vec(srgbToLinear(glm::min(ambient, glm::vec3(1.0f)))) + ",";
  json += "\n\"lights\":[";
  bool firstLight = true;
  for (const LightSource& light : lights) {
    if (light.diffuse == glm::vec3(0.0f)) continue;
    json += firstLight ? "\n  " : ",\n  ";
    firstLight = false;
    const glm::vec3 colour = srgbToLinear(light.diffuse);
    if (light.directional) {
      const glm::vec3 towards =
          glm::length(light.vector) > 0 ? glm::normalize(light.vector) : glm::vec3(0, 0, 1);
      json += "{\"type\":\"sun\",\"towards\":" + vec(towards) + ",\"colour\":" + vec(colour) + "}";
    } else if (light.spot && light.spotCutoff < 90) {
      const glm::vec3 aim = glm::length(light.spotDirection) > 0
                                ? glm::normalize(light.spotDirection)
                                : glm::vec3(0, 0, -1);
      json += "{\"type\":\"spot\",\"position\":" + vec(light.vector) +
              ",\"direction\":" + vec(aim) +
              ",\"cutoff\":" + number(std::max(light.spotCutoff, 0.0f)) +
              ",\"exponent\":" + number(light.spotExponent) + ",\"colour\":" + vec(colour) + "}";
    } else {
      json += "{\"type\":\"point\",\"position\":" + vec(light.vector) +
              ",\"colour\":" + vec(colour) + "}";
    }
  }
  json += "],\n\"materials\":[";
  for (std::size_t i = 0; i < materials_.size(); ++i) {
    const MaterialEntry& m = materials_[i];
    json += fmt::format(
        "{}\n  {{\"name\":{},\"shading\":\"{}\",\"diffuse\":{},\"specular\":{},\"emission\":{},"
        "\"shininess\":{},\"alpha\":{}}}",
        i == 0 ? "" : ",", jsonString(m.name), m.shading == Shading::Hair ? "hair" : "surface",
        vec(srgbToLinear(m.diffuse)), vec(srgbToLinear(m.specular)), vec(srgbToLinear(m.emission)),
        number(m.shininess), number(m.alpha));
  }
  json +=
      "],\n\"meshes\":[" + meshEntries_ + "],\n\"curves\":[" + curveEntries_ + "],\n\"counts\":{";
  bool firstCount = true;
  for (const auto& [what, n] : stats_.organs) {
    json += (firstCount ? "" : ",") + jsonString(what) + ":" + std::to_string(n);
    firstCount = false;
  }
  json += fmt::format(
      "}},\n\"totals\":{{\"meshes\":{},\"triangles\":{},\"curves\":{},"
      "\"points\":{}}}}}\n",
      stats_.meshes, stats_.triangles, stats_.curves, stats_.points);
  const std::uint64_t indexAt = put(json.data(), json.size());
  const std::uint64_t footer[2] = {indexAt, json.size()};
  out_.putBytes(footer, sizeof footer);
  out_.put(std::string_view(kBlenderMagic, 8));
  out_.commit();
  stats_.bytes = out_.bytesWritten();
}

BlenderFileIndex readBlenderIndex(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string name = file.string();
  if (!in) throw std::runtime_error(name + ": cannot open");
  in.seekg(0, std::ios::end);
  BlenderFileIndex index;
  index.fileBytes = static_cast<std::uint64_t>(in.tellg());
  if (index.fileBytes < 16 + kFooterBytes)
    throw std::runtime_error(name + ": not a Hirsute scene for Blender (too short)");
  char head[16], tail[kFooterBytes];
  in.seekg(0);
  in.read(head, sizeof head);
  in.seekg(static_cast<std::streamoff>(index.fileBytes - kFooterBytes));
  in.read(tail, sizeof tail);
  if (!in || std::memcmp(head, kBlenderMagic, 8) != 0 ||
      std::memcmp(tail + 16, kBlenderMagic, 8) != 0)
    throw std::runtime_error(name + ": not a Hirsute scene for Blender (no HIRSUTEB at its ends)");
  std::memcpy(&index.version, head + 8, 4);
  if (index.version != kBlenderVersion)
    throw std::runtime_error(name + ": version " + std::to_string(index.version) +
                             " of the Blender scene; this Hirsute reads version " +
                             std::to_string(kBlenderVersion));
  std::uint64_t length = 0;
  std::memcpy(&index.indexOffset, tail, 8);
  std::memcpy(&length, tail + 8, 8);
  if (index.indexOffset < 16 || length > index.fileBytes ||
      index.indexOffset + length != index.fileBytes - kFooterBytes)
    throw std::runtime_error(name + ": the index is not where the footer says");
  index.json.resize(length);
  in.seekg(static_cast<std::streamoff>(index.indexOffset));
  in.read(index.json.data(), static_cast<std::streamsize>(length));
  if (!in) throw std::runtime_error(name + ": cannot read the index");
  return index;
}

}  // namespace hirsute
