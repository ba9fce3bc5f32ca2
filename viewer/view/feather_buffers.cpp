#include "hirsute/viewer/view/feather_buffers.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <compare>
#include <map>

#include <fmt/format.h>

#include "hirsute/hairs/feathers/feather_instances.h"
#include "hirsute/hairs/feathers/feather_part.h"

namespace hirsute {
namespace {

constexpr int kMaxDetailLevel = 7;
constexpr float kLevelZeroPixels = 16;  // level L covers up to 16·2^L pixels
// A template's blend weights and age are rounded to 1/steps, steps = max(kFewestBlendSteps,
// pixels / kPixelsPerBlendStep) for a feather `pixels` long in the picture (FeatherInstances).
constexpr float kFewestBlendSteps = 32;
constexpr float kPixelsPerBlendStep = 2;

// Sec. 4.3.1: barbs are alpha blended towards their tip.
float tipFade(float s) {
  return std::clamp(1.0f - s * s, 0.0f, 1.0f);
}

glm::vec3 colourOf(const Scene& scene, const FeatherAppearance& appearance) {
  if (appearance.colourKind == FeatherColourKind::Rgb || scene.materials.empty())
    return appearance.colour;
  const int last = static_cast<int>(scene.materials.size()) - 1;
  return scene.materials[static_cast<std::size_t>(std::clamp(appearance.colourIndex, 0, last))]
      .diffuse;
}

const std::vector<glm::vec2>& texcoordsOf(const FeatherGeometry& part,
                                          FeatherTextureMapping mapping) {
  switch (mapping) {
    case FeatherTextureMapping::Vane:
      return part.vertices.vaneUv;
    case FeatherTextureMapping::Growth:
      return part.vertices.growthUv;
    case FeatherTextureMapping::Barb:
      break;
  }
  return part.vertices.barbUv;
}

void appendPart(const Scene& scene, const FeatherGeometry& part, const FeatherMap& toWorld,
                FeatherBuffers& out) {
  const glm::vec3 colour = colourOf(scene, part.appearance);

  const auto shaftBase = static_cast<std::uint32_t>(out.shaftPositions.size());
  for (std::size_t i = 0; i < part.shaft.positions.size(); ++i) {
    const glm::vec3& p = part.shaft.positions[i];
    out.shaftPositions.push_back(toWorld.point(p));
    out.shaftNormals.push_back(toWorld.normal(p, part.shaft.normals[i]));
    out.shaftColors.push_back(colour);
  }
  for (std::uint32_t index : part.shaft.indices) out.shaftIndices.push_back(shaftBase + index);

  FeatherBuffers::Part placed;
  placed.position = toWorld.point(glm::vec3(0.0f));
  placed.left = glm::normalize(toWorld.direction(glm::vec3(0.0f), glm::vec3(0, 1, 0)));
  const bool strips = part.appearance.drawing == BarbStyle::Strips &&
                      part.vertices.stripSides.size() == part.vertices.positions.size();
  const std::vector<glm::vec2>& uv = texcoordsOf(part, part.appearance.textureMapping);
  // A cross-fade of textures is drawn into the barbs' colours, vertex by vertex.
  const std::vector<FeatherTextureLayer>& layers = part.appearance.crossFade;
  auto fadedTexel = [&](std::size_t i) {
    glm::vec3 sum(0.0f);
    for (const FeatherTextureLayer& layer : layers) {
      const std::vector<glm::vec2>& at = texcoordsOf(part, layer.mapping);
      const bool textured = layer.sceneTexture >= 0 &&
                            static_cast<std::size_t>(layer.sceneTexture) < scene.textures.size() &&
                            i < at.size();
      sum += layer.weight *
             (textured ? scene.textures[static_cast<std::size_t>(layer.sceneTexture)].colourAt(at[i])
                       : glm::vec3(1.0f));
    }
    return sum;
  };
  for (int v = 0; v < 2; ++v) {
    FeatherBuffers::Vane& vane = placed.vanes[v];
    vane.left = v == 0;
    vane.primitiveSize = strips ? 3 : 2;
    vane.texture = layers.empty() ? part.appearance.sceneTexture : -1;
    vane.faded = !layers.empty();
    vane.first = static_cast<std::uint32_t>(out.vaneIndices.size());
    for (const Barb& barb : part.barbs) {
      if ((barb.side == BarbSide::Left) != vane.left || barb.vertexCount < 2) continue;
      vane.perBarb = strips ? 4 * (barb.vertexCount - 1) : barb.vertexCount - 1;
      ++out.barbCount;
      out.barbSegments += barb.vertexCount - 1;
      const auto base = static_cast<std::uint32_t>(out.barbPositions.size());
      for (std::uint32_t k = 0; k < barb.vertexCount; ++k) {
        const std::size_t i = barb.firstVertex + k;
        const glm::vec3 p = part.vertices.positions[i];
        const float alpha = tipFade(part.vertices.s[i]);
        const glm::vec2 t = i < uv.size() ? uv[i] : glm::vec2(0.0f);
        const glm::vec3 barbColour = layers.empty() ? colour : colour * fadedTexel(i);
        out.barbPositions.push_back(toWorld.point(p));
        out.barbColors.emplace_back(barbColour, alpha);
        out.barbTexcoords.push_back(t);
        if (strips) {
          // Sec. 4.3.1: two strips either side of the barb, fading away from it. A thinned vane's
          // strips stand for the barbs between them, which the picture cannot tell apart: they
          // keep their alpha to their edges (docs/feathers.md, "Dense coats").
          const glm::vec3 side = part.appearance.stripWidth * part.vertices.stripSides[i];
          const float edgeAlpha = part.barbStride > 1 ? 0.5f * alpha : 0.0f;
          for (float sign : {1.0f, -1.0f}) {
            out.barbPositions.push_back(toWorld.point(p + sign * side));
            out.barbColors.emplace_back(barbColour, edgeAlpha);
            out.barbTexcoords.push_back(t);
          }
        }
      }
      for (std::uint32_t k = 0; k + 1 < barb.vertexCount; ++k) {
        if (!strips) {
          out.vaneIndices.insert(out.vaneIndices.end(), {base + k, base + k + 1});
          continue;
        }
        // Vertex 3k is on the barb, 3k + 1 and 3k + 2 on the two edges.
        const std::uint32_t c0 = base + 3 * k, c1 = c0 + 3;
        out.vaneIndices.insert(out.vaneIndices.end(), {c0 + 1, c0, c1 + 1, c1 + 1, c0, c1, c0,
                                                       c0 + 2, c1, c1, c0 + 2, c1 + 2});
      }
    }
    vane.count = static_cast<std::uint32_t>(out.vaneIndices.size()) - vane.first;
  }
  out.parts.push_back(placed);
}

// Appends the primitives of `vane` (its indices at `begin`) from each barb's tip in to the
// rachis; a segment's primitives stay together.
void appendTipInwards(const FeatherBuffers::Vane& vane,
                      std::vector<std::uint32_t>::const_iterator begin,
                      std::vector<std::uint32_t>& out) {
  if (vane.perBarb == 0) {
    out.insert(out.end(), begin, begin + vane.count);
    return;
  }
  const std::uint32_t perSegment = vane.primitiveSize == 3 ? 4 * 3 : 2;
  const std::uint32_t barbLength = vane.perBarb * vane.primitiveSize;
  for (std::uint32_t barb = 0; barb + barbLength <= vane.count; barb += barbLength) {
    for (std::uint32_t at = barbLength; at >= perSegment; at -= perSegment) {
      out.insert(out.end(), begin + barb + at - perSegment, begin + barb + at);
    }
  }
}

// What makes two feathers one template: their key types, their blend weights and age rounded
// to `steps`, and their level; a bent feather is a template of its own (`own`: its index + 1).
struct TemplateKey {
  std::array<std::uint16_t, 4> types{};
  std::array<std::int32_t, 4> rounded{};  // across[0], across[1], along, age, times steps
  std::uint8_t level = 0;
  std::uint32_t own = 0;
  auto operator<=>(const TemplateKey&) const = default;
};

std::int32_t roundTo(float value, float steps) {
  const float v = std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : 0.0f;
  return static_cast<std::int32_t>(std::lround(v * steps));
}

}  // namespace

std::size_t FeatherInstances::byteSize() const {
  return geometry.byteSize() + templates.size() * sizeof(Template) +
         templateOf.size() * sizeof(std::uint32_t) + toWorld.size() * sizeof(glm::mat4) +
         levels.size();
}

FeatherInstances buildFeatherInstances(const Scene& scene, const std::vector<std::uint8_t>& levels,
                                       bool fullDetail) {
  FeatherInstances out;
  out.levels = levels;
  const FeatherPart& part = scene.organ<FeatherPart>();
  out.templateOf.reserve(part.feathers.size());
  out.toWorld.reserve(part.feathers.size());
  std::map<TemplateKey, std::uint32_t> known;
  for (std::size_t i = 0; i < part.feathers.size(); ++i) {
    const Feather& feather = part.feathers[i];
    const int level = i < levels.size() ? levels[i] : kMaxDetailLevel;
    const float pixels = kLevelZeroPixels * std::exp2(static_cast<float>(level));
    const bool posed = i < part.poses.size() && !part.poses[i].heights.empty();
    // The blend and the age rounded to the level's steps (FeatherInstances), or, in full detail,
    // kept exactly (their bits).
    const float steps = std::max(kFewestBlendSteps, pixels / kPixelsPerBlendStep);
    const std::array<float, 4> values = {feather.across[0], feather.across[1], feather.along,
                                         feather.age};
    TemplateKey key;
    key.types = feather.types;
    for (std::size_t k = 0; k < values.size(); ++k) {
      key.rounded[k] =
          fullDetail ? std::bit_cast<std::int32_t>(values[k]) : roundTo(values[k], steps);
    }
    key.level = static_cast<std::uint8_t>(level);
    key.own = posed ? static_cast<std::uint32_t>(i + 1) : 0;
    auto [found, added] = known.try_emplace(key, static_cast<std::uint32_t>(out.templates.size()));
    if (added) {
      Feather rounded = feather;
      if (!fullDetail) {
        rounded.across = {static_cast<float>(key.rounded[0]) / steps,
                          static_cast<float>(key.rounded[1]) / steps};
        rounded.along = static_cast<float>(key.rounded[2]) / steps;
        rounded.age = static_cast<float>(key.rounded[3]) / steps;
      }
      const FeatherType type = featherTypeOf(scene, rounded);
      const FeatherDetail detail = fullDetail
                                       ? featherDetailForProjectedLength(pixels)
                                       : thinnedFeatherDetail(pixels, type.appearance.drawing);
      const FeatherGeometry geometry = buildFeatherGeometry(type, detail);
      FeatherInstances::Template made;
      made.firstPart = static_cast<std::uint32_t>(out.geometry.parts.size());
      made.firstShaftIndex = static_cast<std::uint32_t>(out.geometry.shaftIndices.size());
      made.barbStride = geometry.barbStride;
      made.firstShaftVertex = static_cast<std::uint32_t>(out.geometry.shaftPositions.size());
      made.firstBarbVertex = static_cast<std::uint32_t>(out.geometry.barbPositions.size());
      const std::size_t verticesBefore =
          out.geometry.shaftPositions.size() + out.geometry.barbPositions.size();
      // A bent feather is built in the world, by its pose; the others in their own frame.
      const FeatherMap map = posed ? FeatherMap::of(scene, i) : FeatherMap(glm::mat4(1.0f));
      forEachFeatherPart(geometry, [&](const FeatherGeometry& piece, bool) {
        appendPart(scene, piece, map, out.geometry);
      });
      made.partCount = static_cast<std::uint32_t>(out.geometry.parts.size()) - made.firstPart;
      made.shaftIndexCount =
          static_cast<std::uint32_t>(out.geometry.shaftIndices.size()) - made.firstShaftIndex;
      made.vertices =
          out.geometry.shaftPositions.size() + out.geometry.barbPositions.size() - verticesBefore;
      made.shaftVertexCount =
          static_cast<std::uint32_t>(out.geometry.shaftPositions.size()) - made.firstShaftVertex;
      made.barbVertexCount =
          static_cast<std::uint32_t>(out.geometry.barbPositions.size()) - made.firstBarbVertex;
      made.primitives = made.shaftIndexCount / 3;
      for (std::uint32_t p = made.firstPart; p < made.firstPart + made.partCount; ++p) {
        for (const FeatherBuffers::Vane& vane : out.geometry.parts[p].vanes) {
          if (vane.primitiveSize > 0) made.primitives += vane.count / vane.primitiveSize;
        }
      }
      out.templates.push_back(made);
    }
    out.templateOf.push_back(found->second);
    out.toWorld.push_back(posed ? glm::mat4(1.0f) : featherToWorld(feather));
    out.drawnVertices += out.templates[found->second].vertices;
    if (out.drawnVertices > part.maxVertices) {
      throw GeometryLimitError(fmt::format(
          "the feathers' geometry grew past {} vertices (--max-vertices) at feather {} of {}, "
          "built at the detail of its size in the picture (a smaller picture, fewer feathers, "
          "or a higher limit)",
          part.maxVertices, i + 1, part.feathers.size()));
    }
  }
  // The nearer vane's order beside the farther's, for every vane.
  std::vector<std::uint32_t> tipInwards;
  for (FeatherBuffers::Part& placed : out.geometry.parts) {
    for (FeatherBuffers::Vane& vane : placed.vanes) {
      vane.tipInwardFirst =
          static_cast<std::uint32_t>(out.geometry.vaneIndices.size() + tipInwards.size());
      appendTipInwards(vane, out.geometry.vaneIndices.cbegin() + vane.first, tipInwards);
    }
  }
  out.geometry.vaneIndices.insert(out.geometry.vaneIndices.end(), tipInwards.begin(),
                                  tipInwards.end());
  out.geometry.levels = levels;
  return out;
}

std::size_t FeatherBuffers::byteSize() const {
  return shaftPositions.size() * sizeof(glm::vec3) * 3 + shaftIndices.size() * 4 +
         barbPositions.size() * (sizeof(glm::vec3) + sizeof(glm::vec4) + sizeof(glm::vec2)) +
         vaneIndices.size() * 4 + parts.size() * sizeof(Part) + levels.size();
}

int featherDetailLevel(float pixels) {
  if (!(pixels > kLevelZeroPixels)) return 0;
  return std::min(kMaxDetailLevel,
                  static_cast<int>(std::ceil(std::log2(pixels / kLevelZeroPixels))));
}

float featherScreenLength(const Scene& scene, const Feather& feather, const Camera& camera) {
  float length = 0;
  for (std::uint16_t type : feather.types) {
    const FeatherType& t = scene.organ<FeatherPart>().types[type - 1u];
    length = std::max(length, t.calamusLength + t.rachisLength);
  }
  length *= feather.size;
  const glm::vec3 middle = feather.position + feather.heading * (0.5f * length);
  const glm::vec4 clip = camera.viewProjection() * glm::vec4(middle, 1);
  const float w = std::max(std::abs(clip.w), 1e-6f);
  return length * std::abs(camera.projectionMatrix[1][1]) / w * 0.5f *
         static_cast<float>(camera.viewport.y);
}

std::vector<std::uint8_t> featherDetailLevels(const Scene& scene, const Camera& camera) {
  std::vector<std::uint8_t> levels;
  levels.reserve(scene.organ<FeatherPart>().feathers.size());
  for (const Feather& feather : scene.organ<FeatherPart>().feathers) {
    levels.push_back(
        static_cast<std::uint8_t>(featherDetailLevel(featherScreenLength(scene, feather, camera))));
  }
  return levels;
}

FeatherBuffers buildFeatherBuffers(const Scene& scene, const std::vector<std::uint8_t>& levels) {
  FeatherBuffers out;
  out.levels = levels;
  const FeatherPart& part = scene.organ<FeatherPart>();
  for (std::size_t i = 0; i < part.feathers.size(); ++i) {
    const Feather& feather = part.feathers[i];
    // The detail follows the picture, so the limit is checked as the feathers are built.
    const std::size_t built = out.shaftPositions.size() + out.barbPositions.size();
    if (built > part.maxVertices) {
      throw GeometryLimitError(fmt::format(
          "the feathers' geometry grew past {} vertices (--max-vertices) at feather {} of {}, "
          "built at the detail of its size in the picture (a smaller picture, fewer feathers, "
          "or a higher limit)",
          part.maxVertices, i + 1, part.feathers.size()));
    }
    const int level = i < levels.size() ? levels[i] : kMaxDetailLevel;
    const FeatherDetail detail =
        featherDetailForProjectedLength(kLevelZeroPixels * std::exp2(static_cast<float>(level)));
    const FeatherGeometry geometry = featherGeometryOf(scene, feather, detail);
    const FeatherMap toWorld = FeatherMap::of(scene, i);
    forEachFeatherPart(geometry, [&](const FeatherGeometry& part, bool) {
      appendPart(scene, part, toWorld, out);
    });
  }
  return out;
}

void orderFeatherBarbs(const FeatherBuffers& buffers, const Camera& camera,
                       std::vector<std::uint32_t>& indices, std::vector<FeatherDrawRun>& runs) {
  indices.clear();
  runs.clear();
  indices.reserve(buffers.vaneIndices.size());
  auto append = [&](const FeatherBuffers::Vane& vane, bool tipInwards) {
    if (vane.count == 0) return;
    const bool triangles = vane.primitiveSize == 3;
    if (runs.empty() || runs.back().texture != vane.texture || runs.back().triangles != triangles) {
      runs.push_back(
          FeatherDrawRun{vane.texture, triangles, static_cast<std::uint32_t>(indices.size()), 0});
    }
    const auto begin = buffers.vaneIndices.cbegin() + vane.first;
    if (!tipInwards) {
      indices.insert(indices.end(), begin, begin + vane.count);
    } else {
      appendTipInwards(vane, begin, indices);
    }
    runs.back().count = static_cast<std::uint32_t>(indices.size()) - runs.back().first;
  };
  for (const FeatherBuffers::Part& part : buffers.parts) {
    const glm::vec3 towardsEye =
        camera.projection == Projection::Perspective ? camera.eye - part.position : -camera.forward;
    const bool leftNearer = glm::dot(part.left, towardsEye) > 0;
    const FeatherBuffers::Vane& nearer = part.vanes[leftNearer ? 0 : 1];
    const FeatherBuffers::Vane& farther = part.vanes[leftNearer ? 1 : 0];
    append(farther, false);
    append(nearer, true);
  }
}

std::vector<glm::vec4> texturedBarbColours(const Scene& scene, const FeatherBuffers& b) {
  // The vanes know their texture; the vertices learn it here.
  std::vector<int> textureOf(b.barbPositions.size(), -1);
  for (const FeatherBuffers::Part& part : b.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      for (std::uint32_t k = 0; k < vane.count; ++k) {
        const std::uint32_t vertex = b.vaneIndices[vane.first + k];
        if (vertex < textureOf.size()) textureOf[vertex] = vane.texture;
      }
    }
  }
  std::vector<glm::vec4> colours(b.barbColors.begin(), b.barbColors.end());
  colours.resize(b.barbPositions.size(), glm::vec4(1.0f));
  for (std::size_t i = 0; i < colours.size() && i < b.barbTexcoords.size(); ++i) {
    const int t = textureOf[i];
    if (t < 0 || static_cast<std::size_t>(t) >= scene.textures.size()) continue;
    const glm::vec3 texel = scene.textures[static_cast<std::size_t>(t)].colourAt(b.barbTexcoords[i]);
    colours[i] = glm::vec4(glm::vec3(colours[i]) * texel, colours[i].a);
  }
  return colours;
}

}  // namespace hirsute
