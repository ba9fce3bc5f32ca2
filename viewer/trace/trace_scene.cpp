#include "hirsute/viewer/trace/trace_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "hirsute/viewer/view/view_lighting.h"

namespace hirsute::trace {
namespace {

void failOnError(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error == RTC_ERROR_NONE) return;
  if (error == RTC_ERROR_OUT_OF_MEMORY) {
    throw std::runtime_error(std::string("the ray tracer ran out of memory ") + what);
  }
  throw std::runtime_error(std::string("Embree failed ") + what + " (error " +
                           std::to_string(static_cast<int>(error)) + ")");
}

template <class T>
T* newBuffer(RTCGeometry geometry, RTCBufferType type, unsigned slot, RTCFormat format,
             std::size_t count, std::size_t& bytes) {
  bytes += sizeof(T) * count;
  return static_cast<T*>(rtcSetNewGeometryBuffer(geometry, type, slot, format, sizeof(T), count));
}

const Material& sceneMaterial(const Scene& scene, int index) {
  static const Material kDefault;
  if (scene.materials.empty()) return kDefault;
  const int last = static_cast<int>(scene.materials.size()) - 1;
  return scene.materials[static_cast<std::size_t>(std::clamp(index, 0, last))];
}

}  // namespace

glm::vec3 linearColour(const glm::vec3& display) {
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    const float v = std::clamp(display[c], 0.0f, 1.0f);
    out[c] = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  }
  return out;
}

TraceScene::TraceScene(const TraceSettings& look, int threads) : look_(look) {
  // The share each colour passes through, the last line for a colour winning: one pass over
  // the lines, however many a view file has.
  for (const auto& [colour, share] : look_.translucent) {
    if (colour < 0) continue;
    const auto slot = static_cast<std::size_t>(colour);
    if (slot >= through_.size()) through_.resize(slot + 1, -1.0f);  // -1: no line
    through_[slot] = std::clamp(share, 0.0f, 1.0f);
  }
  const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : "";
  device_ = rtcNewDevice(config.c_str());
  if (device_ == nullptr) throw std::runtime_error("Embree cannot start (rtcNewDevice failed)");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_COMPACT | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
}

TraceScene::~TraceScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

int TraceScene::addMaterial(const TraceMaterial& material) {
  materials_.push_back(material);
  if (material.opacity < 1) transparency_ = true;
  return static_cast<int>(materials_.size()) - 1;
}

int TraceScene::shownIndex(const Scene& scene, int index, bool lit) const {
  if (!lit) return index;
  return litPaletteEntry(index, litPaletteOffset_, static_cast<int>(scene.materials.size()));
}

int TraceScene::surfaceMaterial(const Scene& scene, int index, bool thin, bool lit) {
  const auto slot = static_cast<std::size_t>(std::max(0, index));
  const std::size_t key = 4 * slot + (thin ? 2 : 0) + (lit ? 1 : 0);
  if (key >= surfaceOf_.size()) surfaceOf_.resize(key + 4, -1);
  if (surfaceOf_[key] >= 0) return surfaceOf_[key];
  const Material& m = sceneMaterial(scene, shownIndex(scene, index, lit));
  const bool named = slot < through_.size() && through_[slot] >= 0;
  TraceMaterial t;
  const glm::vec3 colour = linearColour(m.diffuse);
  if (named) {
    const float through = through_[slot];
    t.surface.reflectance = colour * (1 - through);
    t.surface.transmittance = colour * through;
  } else {
    t.surface.reflectance = colour;
    // A leaf reflects about as much as it passes: kLeafTranslucency of its colour, within what
    // it does not reflect.
    if (thin) t.surface.transmittance = glm::min(colour * kLeafTranslucency, 1.0f - colour);
  }
  t.surface.specular = linearColour(m.specular);
  t.surface.exponent = m.shininess;
  t.opacity = 1 - std::clamp(m.transparency, 0.0f, 1.0f);
  // A thin sheet whose colour has a `subsurface:` line walks light inside instead.
  for (const SubsurfaceSettings& s : look_.subsurface) {
    if (!thin || s.colour != index) continue;
    t.subsurface.meanFreePath = s.meanFreePath;
    t.subsurface.thickness = s.thickness;
    t.subsurface.albedo = s.albedo ? linearColour(*s.albedo) : singleScatteringAlbedo(colour);
  }
  return surfaceOf_[key] = addMaterial(t);
}

const VeinSettings* TraceScene::veinsOf(int index) const {
  for (const VeinSettings& v : look_.veins) {
    if (v.colour == index) return &v;
  }
  return nullptr;
}

int TraceScene::veinedMaterial(const Scene& scene, int index, float aspect, bool thin) {
  const int plain = surfaceMaterial(scene, index, thin);
  const VeinSettings* veins = veinsOf(index);
  if (!veins) return plain;
  const std::size_t slot = 2 * static_cast<std::size_t>(std::max(0, index)) + (thin ? 1 : 0);
  if (slot >= veinedOf_.size()) veinedOf_.resize(slot + 2, -1);
  if (veinedOf_[slot] >= 0) return veinedOf_[slot];
  TraceMaterial t = materials_[static_cast<std::size_t>(plain)];
  std::vector<VeinMap> maps;
  for (int k = 0; k < kVeinVariants; ++k) maps.emplace_back(*veins, aspect, k);
  veinMaps_.push_back(std::move(maps));
  t.veins = static_cast<int>(veinMaps_.size()) - 1;
  // Without a colour of their own, veins are the surface's colour, darker.
  // Kept as the ratio of the veins' colour to the surface's, which scales the reflected and
  // the transmitted light alike.
  const glm::vec3 colour =
      linearColour(sceneMaterial(scene, shownIndex(scene, index, true)).diffuse);
  const glm::vec3 veinColour =
      veins->veinColour ? linearColour(*veins->veinColour) : 0.55f * colour;
  for (int c = 0; c < 3; ++c) t.veinColour[c] = colour[c] > 0 ? veinColour[c] / colour[c] : 1.0f;
  t.veinStrength = veins->strength;
  t.veinBump = veins->bump;
  t.veinWidth = veins->width;
  return veinedOf_[slot] = addMaterial(t);
}

const VeinMap& TraceScene::veinMap(int veins, float variant) const {
  const std::vector<VeinMap>& maps = veinMaps_[static_cast<std::size_t>(veins)];
  const auto k = static_cast<std::size_t>(std::max(0.0f, variant)) % maps.size();
  return maps[k];
}

int TraceScene::hairMaterial(const Scene& scene, int index, int templateNumber) {
  const glm::ivec2 key(index, templateNumber);
  for (const auto& [k, hair] : hairOf_) {
    if (k == key) return hair;
  }
  const Material& m = sceneMaterial(scene, index);
  const int hair = hairOfColour(linearColour(m.diffuse), FibreOrgan::Hairs, templateNumber);
  // A transparent hair material (the crocus's silky hairs) lets that share of rays pass, as GL
  // blends it.
  materials_[static_cast<std::size_t>(hair)].opacity = 1 - std::clamp(m.transparency, 0.0f, 1.0f);
  if (m.transparency > 0) transparency_ = true;
  hairOf_.emplace_back(key, hair);
  return hair;
}

int TraceScene::hairOfColour(const glm::vec3& colour, FibreOrgan organ, int index) {
  TraceMaterial t;
  t.hair = true;
  t.fibre.specular = glm::vec3(std::clamp(look_.hairSpecular, 0.0f, 1.0f));
  t.fibre.diffuse = colour * (1 - t.fibre.specular.x);
  t.fibre.backscatter = look_.hairBackscatter;
  t.fibre.roughness = look_.hairRoughness;
  // The line for these hairs, else the organ's, else Kajiya and Goldman's model: it reaches a
  // clean picture with far fewer samples than the fibre model (docs/trace.md, "Hairs as fibres").
  const FibreSettings* line = nullptr;
  for (const FibreSettings& f : look_.fibres) {
    if (f.organ != organ) continue;
    if (f.index == index && index >= 0) line = &f;
    if (f.index < 0 && !line) line = &f;
  }
  FibreSettings settings = line ? *line : FibreSettings{};
  if (!line) settings.model = FibreModel::KajiyaGoldman;
  if (settings.model == FibreModel::Chiang) {
    t.chiang = true;
    t.chiangFibre.longitudinalRoughness = settings.longitudinalRoughness;
    t.chiangFibre.azimuthalRoughness = settings.azimuthalRoughness;
    t.chiangFibre.tilt = glm::radians(settings.tiltDegrees);
    t.chiangFibre.eta = settings.eta;
    t.fibreColour = settings.colour ? linearColour(*settings.colour) : colour;
    if (settings.melanin) {
      t.absorptionFixed = true;
      t.chiangFibre.absorption = absorptionFromMelanin(settings.melanin->x, settings.melanin->y);
    }
  }
  return addMaterial(t);
}

int TraceScene::surfaceOfColour(const glm::vec3& colour) {
  TraceMaterial t;
  t.surface.reflectance = colour;
  return addMaterial(t);
}

int TraceScene::attach(RTCGeometry geometry, const TraceShape& shape) {
  const unsigned id = rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);  // the scene holds it
  if (id >= shapes_.size()) shapes_.resize(id + 1);
  shapes_[id] = shape;
  return static_cast<int>(id);
}

RTCGeometry TraceScene::geometry(unsigned id) const {
  return rtcGetGeometry(scene_, id);
}

CurveBuffers TraceScene::addCurves(CurveShape shape, std::size_t vertices, std::size_t segments,
                                   int material, bool tint) {
  CurveBuffers out;
  if (segments == 0) return out;
  RTCGeometry g =
      rtcNewGeometry(device_, shape == CurveShape::Round ? RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE
                                                         : RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE);
  out.vertices =
      newBuffer<glm::vec4>(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, vertices, bufferBytes_);
  out.segments = newBuffer<std::uint32_t>(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, segments,
                                          bufferBytes_);
  if (tint) {
    rtcSetGeometryVertexAttributeCount(g, 2);
    out.tint = newBuffer<glm::vec4>(g, RTC_BUFFER_TYPE_VERTEX_ATTRIBUTE, 1, RTC_FORMAT_FLOAT4,
                                    vertices, bufferBytes_);
  }
  failOnError(device_, "making curves");
  curveSegments_ += segments;
  if (tint) transparency_ = true;
  TraceShape traced{material, true, out.vertices, out.segments, nullptr, nullptr, out.tint};
  traced.flatCurve = shape == CurveShape::Flat;
  attach(g, traced);
  return out;
}

int TraceScene::addTexture(const Scene& scene, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= scene.textures.size()) return -1;
  const auto slot = static_cast<std::size_t>(index);
  if (slot >= textureOf_.size()) textureOf_.resize(slot + 1, -2);
  if (textureOf_[slot] != -2) return textureOf_[slot];
  const Texture& t = scene.textures[slot];
  if (t.width <= 0 || t.height <= 0 || t.rgba.empty()) return textureOf_[slot] = -1;
  textures_.push_back(t);
  bufferBytes_ += t.rgba.size();
  return textureOf_[slot] = static_cast<int>(textures_.size()) - 1;
}

TriangleBuffers TraceScene::addTriangles(std::size_t vertices, std::size_t triangles, int material,
                                         bool normals, bool tint, bool surface, int texture) {
  TriangleBuffers out;
  if (triangles == 0) return out;
  RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  out.positions =
      newBuffer<glm::vec3>(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices, bufferBytes_);
  // The index buffer holds three indices an element.
  out.indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), triangles));
  bufferBytes_ += 12 * triangles;
  if (normals || tint) rtcSetGeometryVertexAttributeCount(g, 2);
  if (normals) {
    out.normals = newBuffer<glm::vec3>(g, RTC_BUFFER_TYPE_VERTEX_ATTRIBUTE, 0, RTC_FORMAT_FLOAT3,
                                       vertices, bufferBytes_);
  }
  if (tint) {
    out.tint = newBuffer<glm::vec4>(g, RTC_BUFFER_TYPE_VERTEX_ATTRIBUTE, 1, RTC_FORMAT_FLOAT4,
                                    vertices, bufferBytes_);
    transparency_ = true;
  }
  failOnError(device_, "making triangles");
  if (surface) {
    surfacePoints_.push_back(std::make_unique<SurfacePoint[]>(vertices));
    out.surface = surfacePoints_.back().get();
    bufferBytes_ += sizeof(SurfacePoint) * vertices;
  }
  if (texture >= 0) {
    texcoords_.push_back(std::make_unique<glm::vec2[]>(vertices));
    out.texcoords = texcoords_.back().get();
    bufferBytes_ += sizeof(glm::vec2) * vertices;
  }
  triangles_ += triangles;
  attach(g, TraceShape{material, false, nullptr, nullptr, out.indices, out.normals, out.tint,
                       out.positions, out.surface, out.texcoords, texture});
  return out;
}

void TraceScene::addSpheres(const std::vector<glm::vec4>& centresAndRadii, int material) {
  if (centresAndRadii.empty()) return;
  RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  glm::vec4* v = newBuffer<glm::vec4>(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                      centresAndRadii.size(), bufferBytes_);
  std::copy(centresAndRadii.begin(), centresAndRadii.end(), v);
  failOnError(device_, "making spheres");
  attach(g, TraceShape{material});
}

void TraceScene::addDiscs(const std::vector<glm::vec4>& centresAndRadii,
                          const std::vector<glm::vec3>& normals, int material) {
  std::vector<glm::vec4> facing, oriented;
  std::vector<glm::vec3> orientation;
  for (std::size_t i = 0; i < centresAndRadii.size(); ++i) {
    const glm::vec3 n = i < normals.size() ? normals[i] : glm::vec3(0.0f);
    if (glm::length(n) > 0) {
      oriented.push_back(centresAndRadii[i]);
      orientation.push_back(glm::normalize(n));
    } else {
      facing.push_back(centresAndRadii[i]);
    }
  }
  if (!facing.empty()) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_DISC_POINT);
    glm::vec4* v = newBuffer<glm::vec4>(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                        facing.size(), bufferBytes_);
    std::copy(facing.begin(), facing.end(), v);
    attach(g, TraceShape{material});
  }
  if (!oriented.empty()) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT);
    glm::vec4* v = newBuffer<glm::vec4>(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                        oriented.size(), bufferBytes_);
    std::copy(oriented.begin(), oriented.end(), v);
    glm::vec3* n = newBuffer<glm::vec3>(g, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3,
                                        orientation.size(), bufferBytes_);
    std::copy(orientation.begin(), orientation.end(), n);
    attach(g, TraceShape{material});
  }
  failOnError(device_, "making discs");
}

void TraceScene::commit() {
  const unsigned count = static_cast<unsigned>(shapes_.size());
  for (unsigned id = 0; id < count; ++id) {
    if (RTCGeometry g = rtcGetGeometry(scene_, id)) rtcCommitGeometry(g);
  }
  rtcCommitScene(scene_);
  failOnError(device_, "building its hierarchy");
}

}  // namespace hirsute::trace
