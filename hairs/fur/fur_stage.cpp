#include "hirsute/hairs/fur/fur_stage.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <unordered_map>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hirsute/core/option_checks.h"
#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_settings.h"
#include "hirsute/hairs/fur/fur_strand.h"
#include "hirsute/hairs/fur/fur_strands.h"
#include "hirsute/hairs/fur/fur_texture.h"
#include "hirsute/hairs/fur/wetness_mask.h"
#include "hirsute/hairs/placement/patch_unfolding.h"

namespace hirsute {
namespace {

// The fur record a segment's triangles take: its end's, as hairs do without interpolation (the
// modules before the @Gc that closes a segment apply to it); -1 when the fur there is off.
int furRecordOf(const Scene& scene, const CylinderSegment& segment) {
  const int record = segment.organEnd.of<FurAttributes>();
  if (record < 0) return -1;
  const FurAttributes& fur = scene.organ<FurPart>().attributes[static_cast<std::size_t>(record)];
  if (!fur.enabled() || fur.length <= 0) return -1;
  return record;
}

// What the droplets of a run cost, against the limits: counted before they blend, so that a run
// past a limit stops at once.
class DropletCosts {
 public:
  DropletCosts(const DropletLimits& limits, std::size_t surfaces)
      : limits_(limits), wet_(surfaces, false) {}

  // `count` droplets of `radius` on a mask of size n: each blends its square of texels (what
  // blendDroplet visits), at most the whole mask.
  void chargeTexels(int n, float radius, std::uint64_t count, const SourceLocation& where,
                    const std::string& what) {
    const double size = std::max(n, 0);
    const double side = std::min(size, 2.0 * radius * size + 2);
    const double texels = side * side * static_cast<double>(count);
    if (static_cast<double>(texels_) + texels > static_cast<double>(limits_.texels)) {
      throw DiagnosticError(where, fmt::format("{} would blend more than {} texels of the wetness "
                                               "masks (the limit); use fewer or smaller droplets, "
                                               "or a smaller `wetness mask:` than {}",
                                               what, limits_.texels, n));
    }
    texels_ += static_cast<std::uint64_t>(texels);
  }

  // Surface `index` gets its mask when the first droplet falls on it.
  void chargeMask(std::size_t index, const FurSurface& surface, const SourceLocation& where,
                  const std::string& what) {
    const int n = surface.wetnessSize;
    if (wet_[index] || !surface.wetness.empty() || n <= 0) return;
    wet_[index] = true;
    const auto size = static_cast<std::uint64_t>(n);
    maskBytes_ += size * size * sizeof(glm::vec4);
    if (maskBytes_ > limits_.maskBytes) {
      throw DiagnosticError(where, fmt::format("{} would wet fur surfaces whose wetness masks take "
                                               "more than {} MiB (the limit); use a smaller "
                                               "`wetness mask:` than {} or fewer droplets",
                                               what, limits_.maskBytes >> 20, n));
    }
  }

 private:
  DropletLimits limits_;
  std::uint64_t texels_ = 0, maskBytes_ = 0;
  std::vector<bool> wet_;
};

// sprayDroplets, its costs counted with those of the droplets before.
std::size_t spray(Scene& scene, std::size_t count, float radius, float wetness, std::uint32_t seed,
                  DropletCosts& costs) {
  FurPart& part = scene.organ<FurPart>();
  if (count == 0 || part.surfaces.empty()) return 0;
  const std::string what = fmt::format("{} random droplets (--droplets)", count);
  int largest = 0;
  for (const FurSurface& s : part.surfaces) largest = std::max(largest, s.wetnessSize);
  costs.chargeTexels(largest, radius, count, SourceLocation{}, what);
  std::vector<double> cumulative;
  double total = 0;
  for (const FurSurface& s : part.surfaces) cumulative.push_back(total += s.area);
  if (!(total > 0)) return 0;
  std::mt19937 random(seed);
  auto unit = [&random] { return random() / 4294967296.0; };
  for (std::size_t i = 0; i < count; ++i) {
    const double pick = unit() * total;
    const auto at = static_cast<std::size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
    const std::size_t index = std::min(at, part.surfaces.size() - 1);
    FurSurface& s = part.surfaces[index];
    const glm::vec2 centre(static_cast<float>(unit()), static_cast<float>(unit()));
    costs.chargeMask(index, s, SourceLocation{}, what);
    fur::blendDroplet(s, centre, radius, wetness);
  }
  return count;
}

// A surface under construction: the segments' vertices, and the arc length along the axis of
// each (normalized into v once the surface is complete).
struct SurfaceBuilder {
  FurSurface surface;
  std::vector<float> axisDistance;
  double girthSum = 0;
  int rings = 0;
};

// Appends a segment's rings and strips (its tube vertices: ring k, vertex j at firstVertex +
// k (sides + 1) + j) to the surface.
void appendSegment(const Scene& scene, const CylinderSegment& segment, SurfaceBuilder& b) {
  const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(segment.mesh)];
  const int sides = segment.sides;
  const int rings = static_cast<int>(segment.rings.size());
  FurSurface& s = b.surface;
  const auto base = static_cast<std::uint32_t>(s.positions.size());
  for (int k = 0; k < rings; ++k) {
    const CylinderRing& ring = segment.rings[static_cast<std::size_t>(k)];
    const std::uint32_t first = segment.firstVertex + static_cast<std::uint32_t>(k * (sides + 1));
    for (int j = 0; j <= sides; ++j) {
      const std::uint32_t at = first + static_cast<std::uint32_t>(j);
      const glm::vec3 p = mesh.positions[at];
      glm::vec3 n = mesh.normals[at];
      // Around the girth: the neighbours' chord (the seam's neighbours across it when closed).
      const int before = j > 0 ? j - 1 : (segment.closed ? sides - 1 : 0);
      const int after = j < sides ? j + 1 : (segment.closed ? 1 : sides);
      glm::vec3 along = mesh.positions[first + static_cast<std::uint32_t>(after)] -
                        mesh.positions[first + static_cast<std::uint32_t>(before)];
      n = glm::length(n) > 0 ? glm::normalize(n) : glm::vec3(ring.frame.up);
      along -= glm::dot(along, n) * n;
      if (glm::length(along) < 1e-12f) along = glm::cross(ring.frame.heading, n);
      s.positions.push_back(p);
      s.normals.push_back(n);
      s.tangents.push_back(glm::normalize(along));
      s.uv.emplace_back(static_cast<float>(j) / static_cast<float>(sides), 0.0f);
      b.axisDistance.push_back(ring.axisDistance);
    }
    b.girthSum += (k == 0 ? segment.girthStart : k == rings - 1 ? segment.girthEnd
                          : 0.5f * (segment.girthStart + segment.girthEnd));
    ++b.rings;
  }
  for (int k = 1; k < rings; ++k) {
    for (int j = 0; j < sides; ++j) {
      const std::uint32_t a = base + static_cast<std::uint32_t>((k - 1) * (sides + 1) + j);
      const std::uint32_t c = base + static_cast<std::uint32_t>(k * (sides + 1) + j);
      std::array<std::uint32_t, 6> quad{a, a + 1, c + 1, a, c + 1, c};
      for (int t = 0; t < 2; ++t) {
        std::uint32_t* tri = &quad[static_cast<std::size_t>(3 * t)];
        const glm::vec3 e1 = s.positions[tri[1]] - s.positions[tri[0]];
        const glm::vec3 e2 = s.positions[tri[2]] - s.positions[tri[0]];
        const glm::vec3 face = glm::cross(e1, e2);
        const float area = 0.5f * glm::length(face);
        if (area <= 0) continue;
        // Counter-clockwise seen from the side the fur grows on.
        const glm::vec3 normal = s.normals[tri[0]] + s.normals[tri[1]] + s.normals[tri[2]];
        if (glm::dot(face, normal) < 0) std::swap(tri[1], tri[2]);
        s.indices.insert(s.indices.end(), tri, tri + 3);
        s.area += area;
      }
    }
  }
}

// Whether (u, v, normal) is right-handed over most of the surface's area: u along +dP/du, v
// along +dP/dv and the fur on the side of dP/du × dP/dv, so that a word written into the wetness
// mask reads the right way round from the fur's side.
bool rightHanded(const FurSurface& s, const std::vector<float>& axisDistance) {
  double sum = 0;
  for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3) {
    const std::uint32_t a = s.indices[t], b = s.indices[t + 1], c = s.indices[t + 2];
    const glm::vec2 d1(s.uv[b].x - s.uv[a].x, axisDistance[b] - axisDistance[a]);
    const glm::vec2 d2(s.uv[c].x - s.uv[a].x, axisDistance[c] - axisDistance[a]);
    // Counter-clockwise seen from the fur: the (u, v) triangle turns the same way when the
    // frame is right-handed.
    sum += static_cast<double>(d1.x * d2.y - d1.y * d2.x);
  }
  return sum >= 0;
}

// What every fur surface gets once its triangles and (u, v) are known: strands at rest under the
// settings' force, its layers and strand radius, a dry wetness mask and its fur texture.
void completeSurface(FurSurface&& s, const FurAttributes& fur, const FurSettings& settings,
                     float tile, int textureIndex, Scene& scene) {
  s.tips.resize(s.positions.size());
  for (std::size_t i = 0; i < s.positions.size(); ++i) {
    const fur::StrandRoot strand{s.positions[i], s.normals[i], fur.length};
    s.tips[i] = fur::restingTip(strand, fur.stiffness, fur.mass, settings.force);
  }
  s.layers = settings.layers;
  s.strandRadius = 0.5f * tile / static_cast<float>(settings.textureSize);
  fur::clearWetness(s, settings.wetnessMaskSize);
  s.furTexture = textureIndex;
  scene.organ<FurPart>().surfaces.push_back(std::move(s));
}

void finishSurface(SurfaceBuilder& b, const FurAttributes& fur, const FurSettings& settings,
                   int textureIndex, Scene& scene) {
  FurSurface& s = b.surface;
  if (!rightHanded(s, b.axisDistance)) {
    for (glm::vec2& uv : s.uv) uv.x = 1 - uv.x;
    for (glm::vec3& t : s.tangents) t = -t;
  }
  const auto [lowest, highest] = std::minmax_element(b.axisDistance.begin(), b.axisDistance.end());
  const float start = *lowest, span = std::max(*highest - *lowest, 1e-12f);
  // One tile of the fur texture is size / texelsPerLength fur lengths wide; around the girth
  // a whole number of tiles, so that u = 0 and u = 1 meet without a seam.
  const float tile =
      static_cast<float>(settings.textureSize) * fur.length / settings.texelsPerLength;
  const double girth = b.rings > 0 ? b.girthSum / b.rings : 0.0;
  const float around = std::max(1.0f, std::round(static_cast<float>(girth) / tile));
  s.texcoordsPerUv = glm::vec2(around, span / tile);
  for (std::size_t i = 0; i < s.uv.size(); ++i) {
    s.uv[i].y = (b.axisDistance[i] - start) / span;
    s.texcoords.emplace_back(s.uv[i].x * around, (b.axisDistance[i] - start) / tile);
  }
  completeSurface(std::move(s), fur, settings, tile, textureIndex, scene);
}

// A `~` patch or a polygon with fur on (OrganSurface): (u, v) from its plane coordinates (the
// placement engine's PatchUnfolding: lengths the surface's own on average), both divided by the
// larger extent so that droplets stay round, the fur texture tiled over them in world units.
void addFlatSurface(Scene& scene, const OrganSurface& organ, const TriangleMesh& mesh, int record,
                    const FurSettings& settings, int textureIndex) {
  const PatchUnfolding unfolding(organ, mesh);
  const FurAttributes& fur = scene.organ<FurPart>().attributes[static_cast<std::size_t>(record)];
  FurSurface s;
  s.attributes = record;
  s.material = mesh.material;
  const std::size_t n = organ.uv.size();
  glm::vec2 low(1e30f), high(-1e30f);
  for (std::uint32_t i = 0; i < n; ++i) {
    low = glm::min(low, unfolding.plane(i));
    high = glm::max(high, unfolding.plane(i));
  }
  const float extent = std::max(std::max(high.x - low.x, high.y - low.y), 1e-12f);
  std::vector<glm::vec3> alongU(n, glm::vec3(0.0f));
  for (std::size_t t = 0; t < unfolding.triangles(); ++t) {
    std::array<std::uint32_t, 3> c{unfolding.corner(t, 0), unfolding.corner(t, 1), unfolding.corner(t, 2)};
    const glm::vec3 p0 = unfolding.position(c[0]);
    const glm::vec3 e1 = unfolding.position(c[1]) - p0, e2 = unfolding.position(c[2]) - p0;
    const glm::vec3 face = glm::cross(e1, e2);
    const float area = 0.5f * glm::length(face);
    if (!(area > 0)) continue;
    const glm::vec3 normal = unfolding.normal(c[0]) + unfolding.normal(c[1]) + unfolding.normal(c[2]);
    if (glm::dot(face, normal) < 0) std::swap(c[1], c[2]);
    // World motion per unit of the plane's U over the triangle.
    const glm::vec2 d1 = unfolding.plane(c[1]) - unfolding.plane(c[0]);
    const glm::vec2 d2 = unfolding.plane(c[2]) - unfolding.plane(c[0]);
    const float det = d1.x * d2.y - d1.y * d2.x;
    if (std::abs(det) > 1e-20f) {
      const glm::vec3 q1 = unfolding.position(c[1]) - unfolding.position(c[0]);
      const glm::vec3 q2 = unfolding.position(c[2]) - unfolding.position(c[0]);
      const glm::vec3 perU = (q1 * d2.y - q2 * d1.y) / det;
      for (std::uint32_t k : c) alongU[k] += area * perU;
    }
    s.indices.insert(s.indices.end(), c.begin(), c.end());
    s.area += area;
  }
  if (s.indices.empty()) return;
  std::vector<float> v(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    glm::vec3 normal = unfolding.normal(i);
    normal = glm::length(normal) > 0 ? glm::normalize(normal) : glm::vec3(0, 0, 1);
    glm::vec3 u = alongU[i] - glm::dot(alongU[i], normal) * normal;
    if (glm::length(u) < 1e-20f) u = glm::cross(normal, std::abs(normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
    s.positions.push_back(unfolding.position(i));
    s.normals.push_back(normal);
    s.tangents.push_back(glm::normalize(u));
    const glm::vec2 uv = (unfolding.plane(i) - low) / extent;
    s.uv.push_back(uv);
    v[i] = uv.y;
  }
  if (!rightHanded(s, v)) {
    for (glm::vec2& uv : s.uv) uv.x = 1 - uv.x;
    for (glm::vec3& t : s.tangents) t = -t;
  }
  const float tile =
      static_cast<float>(settings.textureSize) * fur.length / settings.texelsPerLength;
  s.texcoordsPerUv = glm::vec2(extent / tile);
  for (const glm::vec2& uv : s.uv) s.texcoords.push_back(uv * s.texcoordsPerUv);
  completeSurface(std::move(s), fur, settings, tile, textureIndex, scene);
}

// A `~` patch, a polygon or a mesh with fur on. A mesh without texture coordinates that is no
// disc grows its fur through its atlas of charts (OrganSurface::atlasUv): its vertices are
// copied once for each chart they belong to, each copy with its chart's (u, v), so that the
// fur's surface lies flat chart by chart as a file's atlas does.
void addOrganSurface(Scene& scene, const OrganSurface& organ, int record,
                     const FurSettings& settings, int textureIndex) {
  const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(organ.mesh)];
  const std::size_t triangles = organ.indexCount / 3;
  if (organ.kind != OrganSurfaceKind::Mesh || organ.atlasUv.size() != 3 * triangles ||
      organ.atlasChart.size() != triangles) {
    addFlatSurface(scene, organ, mesh, record, settings, textureIndex);
    return;
  }
  TriangleMesh charts;
  charts.material = mesh.material;
  OrganSurface cut;
  cut.kind = organ.kind;
  cut.organs = organ.organs;
  std::unordered_map<std::uint64_t, std::uint32_t> copyOf;  // (chart, vertex) → its copy
  for (std::size_t t = 0; t < triangles; ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t vertex = mesh.indices[organ.firstIndex + 3 * t + k];
      const std::uint64_t key = static_cast<std::uint64_t>(organ.atlasChart[t]) << 32 | vertex;
      const auto [at, added] =
          copyOf.emplace(key, static_cast<std::uint32_t>(charts.positions.size()));
      if (added) {
        charts.positions.push_back(mesh.positions[vertex]);
        charts.normals.push_back(mesh.normals[vertex]);
        cut.uv.push_back(organ.atlasUv[3 * t + k]);
      }
      charts.indices.push_back(at->second);
    }
  }
  cut.indexCount = static_cast<std::uint32_t>(charts.indices.size());
  addFlatSurface(scene, cut, charts, record, settings, textureIndex);
}

}  // namespace

bool hasFur(const Scene& scene) {
  for (const FurAttributes& fur : scene.organ<FurPart>().attributes) {
    if (fur.enabled()) return true;
  }
  return false;
}

FurStageReport growFur(Scene& scene, const ModelResources& resources,
                       const FurStageOptions& options, Diagnostics& diagnostics) {
  FurPart& part = scene.organ<FurPart>();
  const FurSettings& settings = resources.view.organ<FurSettings>();
  FurStageReport report;
  part.maxVertices = options.maxVertices;
  part.surfaces.clear();
  part.textures.clear();
  std::map<float, int> textureForDensity;
  auto textureFor = [&](float density) {
    const auto found = textureForDensity.find(density);
    if (found != textureForDensity.end()) return found->second;
    part.textures.push_back(
        fur::makeFurTexture(settings.textureSize, settings.textureSeed, density));
    const int index = static_cast<int>(part.textures.size() - 1);
    textureForDensity.emplace(density, index);
    return index;
  };

  SurfaceBuilder builder;
  int openRecord = -1, openTube = -1;
  auto close = [&] {
    if (openRecord >= 0 && !builder.surface.indices.empty()) {
      if (part.surfaces.size() >= options.maxSurfaces)
        throw DiagnosticError(SourceLocation{}, "more than " + std::to_string(options.maxSurfaces) +
                                                    " fur surfaces (each run of furry cylinder segments is one)");
      const FurAttributes& fur = part.attributes[static_cast<std::size_t>(openRecord)];
      builder.surface.attributes = openRecord;
      finishSurface(builder, fur, settings, textureFor(fur.density), scene);
    }
    builder = SurfaceBuilder{};
    openRecord = -1;
  };
  for (const CylinderSegment& segment : scene.cylinderSegments) {
    const int record = furRecordOf(scene, segment);
    const bool drawn = segment.mesh >= 0 && segment.sides > 0 && segment.vertexCount > 0 &&
                       segment.rings.size() >= 2;
    if (record < 0 || !drawn || record != openRecord || segment.tube != openTube) close();
    if (record < 0 || !drawn) continue;
    if (openRecord < 0) {
      openRecord = record;
      openTube = segment.tube;
      builder.surface.material = scene.meshes[static_cast<std::size_t>(segment.mesh)].material;
      builder.surface.wrapsU = segment.closed;
    }
    appendSegment(scene, segment, builder);
  }
  close();
  // Bicubic patches and polygons, each a fur surface of its own.
  for (const OrganSurface& organ : scene.organSurfaces) {
    const int record = organ.organs.of<FurAttributes>();
    if (record < 0 || organ.mesh < 0) continue;
    const FurAttributes& fur = part.attributes[static_cast<std::size_t>(record)];
    if (!fur.enabled() || fur.length <= 0) continue;
    if (part.surfaces.size() >= options.maxSurfaces)
      throw DiagnosticError(SourceLocation{}, "more than " + std::to_string(options.maxSurfaces) + " fur surfaces");
    addOrganSurface(scene, organ, record, settings, textureFor(fur.density));
  }

  // The view file's droplets: counted first, each on the surfaces it falls on, then blended.
  DropletCosts costs(options.dropletLimits, part.surfaces.size());
  const auto fallsOn = [&part](const Droplet& d, std::size_t i) {
    return i < part.surfaces.size() &&
           (d.surface == 0 || static_cast<std::size_t>(d.surface - 1) == i);
  };
  for (const Droplet& d : settings.droplets) {
    if (d.surface > static_cast<int>(part.surfaces.size())) {
      throw DiagnosticError(d.where, "no fur surface " + std::to_string(d.surface) +
                                         " (the model has " + std::to_string(part.surfaces.size()) +
                                         ")");
    }
    for (std::size_t i = 0; i < part.surfaces.size(); ++i) {
      if (!fallsOn(d, i)) continue;
      const FurSurface& surface = part.surfaces[i];
      costs.chargeTexels(surface.wetnessSize, d.radius, 1, d.where, "the view file's droplets");
      costs.chargeMask(i, surface, d.where, "the view file's droplets");
    }
  }
  for (const Droplet& d : settings.droplets) {
    for (std::size_t i = 0; i < part.surfaces.size(); ++i) {
      if (fallsOn(d, i)) fur::blendDroplet(part.surfaces[i], d.centre, d.radius, d.wetness);
    }
    ++report.droplets;
  }
  if (!settings.droplets.empty() && part.surfaces.empty())
    diagnostics.warn(settings.droplets.front().where,
                     "the model has no fur for the droplets to fall on");
  report.droplets += spray(scene, options.droplets, options.dropletRadius, options.dropletWetness,
                           options.dropletSeed, costs);
  // A curl that turns more often than an exported strand's points can follow is smoothed.
  for (const FurSurface& s : part.surfaces) {
    if (s.attributes < 0) continue;
    const FurAttributes& fur = part.attributes[static_cast<std::size_t>(s.attributes)];
    if (fur::strandSamplesCapped(fur)) {
      diagnostics.warn(SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0},
                       fmt::format("a fur curl of {:g} radians over the length (@Uc) turns more "
                                   "than {} times: exported strands follow it with {} points "
                                   "and smooth it",
                                   fur.curlFrequency, (fur::kMaxStrandSamples - 1) / fur::kSamplesPerTurn,
                                   fur::kMaxStrandSamples));
      break;
    }
  }
  report.surfaces = part.surfaces.size();
  for (const FurSurface& s : part.surfaces) {
    report.triangles += s.triangleCount();
    report.area += s.area;
  }
  return report;
}

std::size_t sprayDroplets(Scene& scene, std::size_t count, float radius, float wetness,
                          std::uint32_t seed, const DropletLimits& limits) {
  DropletCosts costs(limits, scene.organ<FurPart>().surfaces.size());
  return spray(scene, count, radius, wetness, seed, costs);
}

}  // namespace hirsute

namespace hirsute {
namespace {

struct FurCommandOptions : OrganOptionsOf<FurCommandOptions> {
  FurStageOptions stage;
};

class FurStage : public OrganStageOf<FurCommandOptions> {
 public:
  const char* activity() const override { return "growing fur"; }

  bool wanted(const Scene& scene, const ModelResources&) const override { return hasFur(scene); }

 protected:
  void declareOptions(CLI::App& command, FurCommandOptions& s) const override {
    command.add_flag("!--no-fur", s.enabled, "Leave out the fur (@U modules)");
    command
        .add_option("--droplets", s.stage.droplets,
                    "Random droplets of water on the fur (docs/fur.md)")
        ->check(CLI::Range(0, 10'000'000));
    command
        .add_option(
            "--droplet-radius", s.stage.dropletRadius,
            "Radius of the random droplets, in the fur surface's [0, 1] units (default 0.05)")
        ->check(finiteRange(1e-6, 1.0));
    command
        .add_option("--droplet-wetness", s.stage.dropletWetness,
                    "Wetness of the random droplets, 0 to 1 (default 1)")
        ->check(finiteRange(0.0, 1.0));
    command.add_option("--droplet-seed", s.stage.dropletSeed,
                       "Seed of the random droplets (default 1)");
  }
  std::string growFrom(const OrganStageRun& run, const FurCommandOptions& options) const override {
    FurStageOptions stage = options.stage;
    stage.lsystemFile = run.lsystemFile;
    stage.maxVertices = run.maxVertices;
    const FurStageReport report = growFur(run.scene, run.resources, stage, run.diagnostics);
    return fmt::format("fur: {} surfaces, {} triangles, {:.4g} units², {} droplets",
                       report.surfaces, report.triangles, report.area, report.droplets);
  }
};

}  // namespace

const OrganStage& furStage() {
  static const FurStage stage;
  return stage;
}

}  // namespace hirsute
