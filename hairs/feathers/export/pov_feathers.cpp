// Feathers in the POV-Ray scene (docs/design.md and docs/export.md, "Feathers"): built at the
// level of detail of their size in the scene's image (--width, --height), as the GL renderer
// builds them (feather_buffers.h), one level finer, their barbs thinned as GL thins them, and
// written as instances (FeatherInstances): each template once, `#declare FeatherK=mesh2{…}` of
// its shaft and barbs in its own frame, and every feather an `object{FeatherK matrix<…>}`, so that
// POV-Ray parses and holds each template once, however many feathers share it. The barbs'
// vertices carry their colour and a transparency that fades to the barb tips (and, on strips, to
// their edges), interpolated across each triangle as POV-Ray does for a face with three texture
// indices; the shaft's are opaque. Polyline barbs become thin ribbons facing the feather's front,
// since POV-Ray has no lines. A textured type's barbs take its texture's colour at each vertex,
// times the type's colour, as GL's barb shader does (at a still's detail the barbs sample it
// densely). With --full-feathers every feather is built whole, every barb, into two meshes (the
// shafts, the barbs), as before instancing.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_writer.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/view/feather_buffers.h"

namespace hirsute {
namespace {

constexpr float kRibbonShare = 0.3f;  // a polyline barb's ribbon: this share of the spacing
constexpr char kLitFinish[] = "ambient 0.2 diffuse 0.7";

// The barb triangles of `part` into `triangles`: strips as they are, polyline barbs as ribbons
// whose vertices are added to `positions` and `colours`. Each segment (i, j) a quad across the
// barb in the vane plane.
void appendBarbTriangles(const FeatherBuffers& b, const FeatherBuffers::Part& part,
                         std::vector<glm::vec3>& positions, std::vector<glm::vec4>& colours,
                         std::vector<std::uint32_t>& triangles) {
  for (const FeatherBuffers::Vane& vane : part.vanes) {
    const auto begin = b.vaneIndices.begin() + vane.first;
    if (vane.primitiveSize == 3) {
      triangles.insert(triangles.end(), begin, begin + vane.count);
      continue;
    }
    for (std::uint32_t k = 0; k + 1 < vane.count; k += 2) {
      const std::uint32_t i = begin[k], j = begin[k + 1];
      const glm::vec3 along = positions[j] - positions[i];
      glm::vec3 across = glm::cross(along, glm::cross(part.left, along));
      const float length = glm::length(across);
      if (!(length > 0)) continue;
      across *= kRibbonShare * 0.5f * glm::length(along) / length;
      const auto base = static_cast<std::uint32_t>(positions.size());
      for (std::uint32_t v : {i, j}) {
        positions.push_back(positions[v] + across);
        positions.push_back(positions[v] - across);
        colours.push_back(colours[v]);
        colours.push_back(colours[v]);
      }
      triangles.insert(triangles.end(), {base, base + 1, base + 2, base + 2, base + 1, base + 3});
    }
  }
}

// The barbs of a thinned `part` as opaque ribbons of the coverage its blended strips have: a
// ray through a coat's layers of transparent strips pays a traversal of the scene for every
// layer, even where a strip's alpha is near 0 (POV-Ray does not count transmitted rays towards
// max_trace_level), which made a coat's time grow with the square of its density; an opaque
// ribbon stops the ray. Each strip segment (a thinned vane's two strips w wide, their alpha a at
// the barb and a/2 at their edges, feather_buffers.cpp) becomes a ribbon a·w/2 either side of
// the barb, and a polyline segment one a·(its ribbon's width); alpha falls to the tip, so the
// ribbons taper (Sec. 4.3.1's fading, carried as width). Antialiasing averages them as GL blends
// the strips. The share, a/2 rather than the strips' alpha-weighted 3a/4, is the one whose
// picture came nearest POV-Ray's own of the transparent strips (docs/feathers.md, "Dense coats").
void appendCoverageRibbons(const FeatherBuffers& b, const FeatherBuffers::Part& part,
                           std::vector<glm::vec3>& positions, std::vector<glm::vec4>& colours,
                           std::vector<std::uint32_t>& triangles) {
  auto quad = [&](const glm::vec3& l0, const glm::vec3& r0, const glm::vec3& l1,
                  const glm::vec3& r1, const glm::vec4& c0, const glm::vec4& c1) {
    if (!(glm::length(glm::cross(r1 - l0, l1 - r0)) > 0)) return;
    const auto base = static_cast<std::uint32_t>(positions.size());
    positions.insert(positions.end(), {l0, r0, l1, r1});
    const glm::vec4 opaque0(glm::vec3(c0), 1.0f), opaque1(glm::vec3(c1), 1.0f);
    colours.insert(colours.end(), {opaque0, opaque0, opaque1, opaque1});
    triangles.insert(triangles.end(), {base, base + 1, base + 2, base + 2, base + 1, base + 3});
  };
  for (const FeatherBuffers::Vane& vane : part.vanes) {
    const auto begin = b.vaneIndices.begin() + vane.first;
    if (vane.primitiveSize == 3) {
      // A segment's twelve indices (feather_buffers.cpp): c0 + 1, c0, c1 + 1, c1 + 1, c0, c1,
      // c0, c0 + 2, c1, c1, c0 + 2, c1 + 2; c0 + 1 and c0 + 2 are c0's strip edges.
      for (std::uint32_t k = 0; k + 12 <= vane.count; k += 12) {
        const std::uint32_t c0 = begin[k + 1], c1 = begin[k + 5];
        const float a0 = 0.5f * colours[c0].a, a1 = 0.5f * colours[c1].a;
        const glm::vec3 p0 = positions[c0], p1 = positions[c1];
        quad(p0 + a0 * (positions[c0 + 1] - p0), p0 + a0 * (positions[c0 + 2] - p0),
             p1 + a1 * (positions[c1 + 1] - p1), p1 + a1 * (positions[c1 + 2] - p1), colours[c0],
             colours[c1]);
      }
      continue;
    }
    for (std::uint32_t k = 0; k + 1 < vane.count; k += 2) {
      const std::uint32_t i = begin[k], j = begin[k + 1];
      const glm::vec3 along = positions[j] - positions[i];
      glm::vec3 across = glm::cross(along, glm::cross(part.left, along));
      const float length = glm::length(across);
      if (!(length > 0)) continue;
      across *= kRibbonShare * 0.5f * glm::length(along) / length;
      const float ai = colours[i].a, aj = colours[j].a;
      quad(positions[i] + ai * across, positions[i] - ai * across, positions[j] + aj * across,
           positions[j] - aj * across, colours[i], colours[j]);
    }
  }
}

// Every feather built whole, in the world, into two meshes (--full-feathers).
void writeWhole(const Scene& scene, const std::vector<std::uint8_t>& levels, PovWriter& pov) {
  using Shade = PovWriter::Shade;
  FeatherBuffers b = buildFeatherBuffers(scene, levels);
  std::vector<std::uint32_t> triangles;
  std::vector<glm::vec3> positions = b.barbPositions;
  std::vector<glm::vec4> colours = texturedBarbColours(scene, b);
  for (const FeatherBuffers::Part& part : b.parts)
    appendBarbTriangles(b, part, positions, colours, triangles);
  if (!b.shaftIndices.empty()) {
    std::vector<Shade> shades;
    shades.reserve(b.shaftColors.size());
    for (const glm::vec3& c : b.shaftColors) shades.push_back(PovWriter::shadeOf(c, 1));
    pov.writeShadedMesh("feather shafts", b.shaftPositions, shades, b.shaftIndices, kLitFinish);
  }
  if (!triangles.empty()) {
    std::vector<Shade> shades;
    shades.reserve(colours.size());
    for (const glm::vec4& c : colours) shades.push_back(PovWriter::shadeOf(glm::vec3(c), c.a));
    pov.writeShadedMesh("feather barbs", positions, shades, triangles, kLitFinish);
  }
}

// Each template declared once, each feather an object of it.
void writeInstances(const Scene& scene, const std::vector<std::uint8_t>& levels, PovWriter& pov) {
  using Shade = PovWriter::Shade;
  const FeatherInstances instances = buildFeatherInstances(scene, levels, false);
  const FeatherBuffers& b = instances.geometry;
  std::vector<glm::vec3> positions = b.barbPositions;
  std::vector<glm::vec4> colours = texturedBarbColours(scene, b);
  // A template's vertices, numbered from 0: its shaft's, then its barbs' as its triangles use
  // them (barb vertex v is local[v] when stamp[v] is the template's).
  std::vector<std::uint32_t> local, stamp;
  std::vector<glm::vec3> points;
  std::vector<Shade> shades;
  std::vector<std::uint32_t> barbTriangles, faces;
  // Templates are written in the file's units, at the feather's own size 1: finer than the scene.
  NumberFormat& format = pov.positionFormat();
  const NumberFormat sceneFormat = format;
  format.decimals = std::max(format.decimals, 5);
  std::vector<bool> used(instances.templates.size(), false);
  for (std::uint32_t t : instances.templateOf) used[t] = true;
  for (std::size_t t = 0; t < instances.templates.size(); ++t) {
    if (!used[t]) continue;
    const FeatherInstances::Template& made = instances.templates[t];
    points.clear();
    shades.clear();
    faces.clear();
    barbTriangles.clear();
    for (std::uint32_t v = 0; v < made.shaftVertexCount; ++v) {
      points.push_back(b.shaftPositions[made.firstShaftVertex + v]);
      shades.push_back(PovWriter::shadeOf(b.shaftColors[made.firstShaftVertex + v], 1));
    }
    for (std::uint32_t k = 0; k < made.shaftIndexCount; ++k)
      faces.push_back(b.shaftIndices[made.firstShaftIndex + k] - made.firstShaftVertex);
    for (std::uint32_t p = made.firstPart; p < made.firstPart + made.partCount; ++p) {
      if (made.barbStride > 1) {
        appendCoverageRibbons(b, b.parts[p], positions, colours, barbTriangles);
      } else {
        appendBarbTriangles(b, b.parts[p], positions, colours, barbTriangles);
      }
    }
    local.resize(positions.size());
    stamp.resize(positions.size(), 0);
    for (std::uint32_t v : barbTriangles) {
      if (stamp[v] != t + 1) {
        stamp[v] = static_cast<std::uint32_t>(t + 1);
        local[v] = static_cast<std::uint32_t>(points.size());
        points.push_back(positions[v]);
        shades.push_back(PovWriter::shadeOf(glm::vec3(colours[v]), colours[v].a));
      }
      faces.push_back(local[v]);
    }
    if (faces.empty()) continue;
    pov.writeShadedMesh("feather barbs and shaft, template " + std::to_string(t), points, shades,
                        faces, kLitFinish, "Feather" + std::to_string(t));
  }
  format = sceneFormat;
  // The instances, in the Scene's order. POV-Ray's matrix is row-vector: its rows are the images
  // of x, y, z and the translation, which are glm's columns.
  ExportFile& out = pov.out();
  out.put("\n// feathers: instances of the templates above\n");
  std::size_t placed = 0;
  for (std::size_t i = 0; i < instances.templateOf.size(); ++i) {
    const std::uint32_t t = instances.templateOf[i];
    const FeatherInstances::Template& made = instances.templates[t];
    if (made.shaftIndexCount == 0 && made.primitives == 0) continue;
    out.put("object{Feather");
    out.putInteger(static_cast<std::int64_t>(t));
    const glm::mat4& m = instances.toWorld[i];
    if (m != glm::mat4(1.0f)) {
      out.put(" matrix<");
      for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 3; ++row) {
          if (column + row > 0) out.put(',');
          pov.number(m[column][row], column == 3 ? sceneFormat : NumberFormat{6, false});
        }
      }
      out.put('>');
    }
    out.put("}\n");
    ++placed;
  }
  pov.count("feather templates", instances.templates.size());
  pov.count("feather objects", placed);
}

}  // namespace

void FeatherWriter::writePov(const Scene& scene, PovWriter& pov) const {
  const FeatherPart& part = scene.organ<FeatherPart>();
  if (part.feathers.empty()) return;
  // A still is looked at closer than a preview: one level finer than the camera asks for.
  std::vector<std::uint8_t> levels = featherDetailLevels(scene, pov.camera());
  for (std::uint8_t& level : levels) level = static_cast<std::uint8_t>(std::min(level + 1, 7));
  if (part.fullDetail) {
    writeWhole(scene, levels, pov);
  } else {
    writeInstances(scene, levels, pov);
  }
  pov.count("feathers", part.feathers.size());
}

}  // namespace hirsute
