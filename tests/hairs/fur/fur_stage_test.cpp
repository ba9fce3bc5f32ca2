// The fur stage and the explicit strands on the shipped models (models/fur-torus,
// models/fur-square): the torus is one fur surface of the paper's 9 360 triangles, its (u, v)
// covers [0, 1]² continuously around the ring; exported strands number the texture's fill times
// the area and show the curl of Eq. 4 with its radius and frequency; wet strands do not curl and
// lean towards their clump's centre; the view file's droplets land in the mask.
#include "hirsute/hairs/fur/fur_stage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <utility>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_settings.h"
#include "hirsute/hairs/fur/fur_strand.h"
#include "hirsute/hairs/fur/fur_strands.h"
#include "hirsute/hairs/fur/wetness_mask.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";
constexpr double kPi = 3.14159265358979;

struct Built {
  ModelResources resources;
  Model model;
  Scene scene;
  Diagnostics diagnostics;
  FurStageReport report;
};

// Derived, interpreted and given its fur as `hirsute render` does (cli/model_pipeline.cpp).
void build(Built& out, const fs::path& lsystem, const fs::path& view, FurStageOptions options = {}) {
  out.resources = loadModelResources(view, {}, out.diagnostics);
  out.model = loadModel(lsystem, view, out.diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(out.model.program, out.diagnostics, &out.model.functions, out.model.folder,
                      printed);
  Derivation derivation(out.model.program, evaluator, out.diagnostics);
  installQueryPass(derivation, out.resources, out.diagnostics);
  derivation.run();
  interpret(derivation, out.resources, out.scene, out.diagnostics);
  out.report = growFur(out.scene, out.resources, options, out.diagnostics);
}

void buildTorus(Built& b, const char* view = "torus.v") {
  build(b, kModels / "fur-torus" / "torus.l", kModels / "fur-torus" / view);
}

// The component of `offset` in the tangent plane of unit normal n.
glm::dvec3 tangential(const glm::dvec3& offset, const glm::dvec3& n) { return offset - glm::dot(offset, n) * n; }

// @Ut(i) is the view file's i-th texture, counted from 1 (models/fur-square/spotted.v declares
// stripes, then spots); @Ut(0) the surface's colour.
TEST(FurStage, UtNamesTheViewFilesTextureCountingFromOne) {
  const fs::path folder = kModels / "fur-square";
  Built spotted;
  build(spotted, folder / "spotted.l", folder / "spotted.v");
  const FurPart& part = spotted.scene.organ<FurPart>();
  ASSERT_FALSE(part.surfaces.empty());
  ASSERT_EQ(spotted.scene.textures.size(), 2u);
  for (const FurSurface& surface : part.surfaces) {
    const FurAttributes& a = part.attributes[static_cast<std::size_t>(surface.attributes)];
    const Texture* texture = fur::colourTexture(spotted.scene, a);
    ASSERT_NE(texture, nullptr);
    EXPECT_EQ(fs::path(texture->file).filename(), "spots.png");
  }
  // The same square with @Ut(1), and with @Ut(0).
  const fs::path scratch = fs::temp_directory_path() / "hirsute_fur_ut_test";
  fs::create_directories(scratch);
  for (const char* file : {"spotted.v", "square.v", "flat.con", "square.map", "stripes.png", "spots.png"}) {
    fs::copy_file(folder / file, scratch / file, fs::copy_options::overwrite_existing);
  }
  std::ifstream in(folder / "spotted.l");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [coat, expected] : {std::pair{"1", "stripes.png"}, std::pair{"0", ""}}) {
    std::string changed = text;
    changed.replace(changed.find("#define COAT 2"), 14, std::string("#define COAT ") + coat);
    std::ofstream(scratch / "coat.l") << changed;
    Built b;
    build(b, scratch / "coat.l", scratch / "spotted.v");
    const FurPart& p = b.scene.organ<FurPart>();
    ASSERT_FALSE(p.surfaces.empty());
    const Texture* texture = fur::colourTexture(
        b.scene, p.attributes[static_cast<std::size_t>(p.surfaces.front().attributes)]);
    if (*expected == 0) {
      EXPECT_EQ(texture, nullptr);
    } else {
      ASSERT_NE(texture, nullptr);
      EXPECT_EQ(fs::path(texture->file).filename(), expected);
    }
  }
  fs::remove_all(scratch);
}

TEST(FurStage, TorusIsOneSurfaceOfThePapersTriangles) {
  Built b;
  buildTorus(b);
  ASSERT_EQ(b.scene.organ<FurPart>().surfaces.size(), 1u);
  const FurSurface& s = b.scene.organ<FurPart>().surfaces[0];
  EXPECT_EQ(s.triangleCount(), 9360u);
  EXPECT_TRUE(s.wrapsU);
  // A ring of radius 3 around a tube of radius 1: 4 pi² R r, less the polygons' shortfall.
  EXPECT_NEAR(s.area, 4 * kPi * kPi * 3, 0.01 * 4 * kPi * kPi * 3);
  float lowest = 1, highest = 0;
  for (std::size_t i = 0; i < s.uv.size(); ++i) {
    EXPECT_GE(s.uv[i].x, 0.0f);
    EXPECT_LE(s.uv[i].x, 1.0f);
    lowest = std::min(lowest, s.uv[i].y);
    highest = std::max(highest, s.uv[i].y);
    EXPECT_NEAR(glm::length(s.normals[i]), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(s.normals[i], s.tangents[i]), 0.0f, 1e-5f);
    // At rest without a force, the particle is p_0.
    EXPECT_LT(glm::distance(s.tips[i], s.positions[i] + 0.35f * s.normals[i]), 1e-5f);
  }
  EXPECT_EQ(lowest, 0.0f);
  EXPECT_EQ(highest, 1.0f);
  // Continuous along the axis: vertices at one place have one (u, v) (the segments' shared
  // rings; u = 0 and u = 1 meet at the girth's seam).
  for (std::size_t i = 0; i < s.positions.size(); ++i) {
    for (std::size_t j = i + 1; j < std::min(s.positions.size(), i + 2000); ++j) {
      if (glm::distance(s.positions[i], s.positions[j]) > 1e-5f) continue;
      const float du = std::abs(s.uv[i].x - s.uv[j].x);
      EXPECT_TRUE(du < 1e-5f || std::abs(du - 1) < 1e-5f) << i << " " << j;
      EXPECT_NEAR(s.uv[i].y, s.uv[j].y, 1e-5f);
    }
  }
}

TEST(FurStage, ExportedStrandCountIsTheFillTimesTheArea) {
  Built b;
  buildTorus(b);
  const FurSurface& s = b.scene.organ<FurPart>().surfaces[0];
  const FurAttributes& fur =
      b.scene.organ<FurPart>().attributes[static_cast<std::size_t>(s.attributes)];
  const double texel =
      fur.length / b.resources.view.organ<FurSettings>().texelsPerLength;  // world units
  const double expected = fur.density * s.area / (texel * texel);
  const std::size_t strands = fur::countStrands(b.scene, s);
  EXPECT_NEAR(static_cast<double>(strands), expected, 0.03 * expected);
  std::size_t emitted = 0;
  fur::forEachStrand(b.scene, s, 4, [&](const fur::FurStrandView& strand) {
    ++emitted;
    EXPECT_EQ(strand.points.size(), 4u);
    EXPECT_NEAR(strand.radius, 0.5 * texel, 1e-6);
  });
  EXPECT_EQ(emitted, strands);
}

// The part of each point of a strand across its normal, from the root: the curl (and any clump
// shift), since a strand at rest rises along the normal.
std::vector<glm::dvec3> across(const fur::FurStrandView& strand) {
  std::vector<glm::dvec3> out;
  const glm::dvec3 root = strand.points[0], n = strand.normal;
  for (const glm::vec3& p : strand.points) out.push_back(tangential(glm::dvec3(p) - root, n));
  return out;
}

// The angle from a to b about n, in (-pi, pi].
double turn(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& n) {
  return std::atan2(glm::dot(glm::cross(a, b), n), glm::dot(a, b));
}

TEST(FurStage, CurlOfExportedStrandsHasItsRadiusAndFrequency) {
  Built b;
  buildTorus(b);
  FurAttributes& fur =
      b.scene.organ<FurPart>()
          .attributes[static_cast<std::size_t>(b.scene.organ<FurPart>().surfaces[0].attributes)];
  fur.curlRadius = 0.3f;
  fur.curlFrequency = static_cast<float>(4 * kPi);  // two turns over the length
  const int samples = 41;
  std::size_t measured = 0;
  fur::forEachStrand(
      b.scene, b.scene.organ<FurPart>().surfaces[0], samples,
      [&](const fur::FurStrandView& strand) {
        if (measured++ >= 300) return;
        const std::vector<glm::dvec3> side = across(strand);
        double winding = 0;
        for (int i = 1; i < samples; ++i) {
          const double h = strand.reach * i / (samples - 1.0);
          // alpha(h) = K_alpha L h: the radius grows linearly along the strand.
          ASSERT_NEAR(glm::length(side[static_cast<std::size_t>(i)]), 0.3 * 0.35 * h, 1e-4);
          // The rise along the normal is the rest strand's, (2h - h²) L.
          const double rise = glm::dot(
              glm::dvec3(strand.points[static_cast<std::size_t>(i)]) - glm::dvec3(strand.points[0]),
              glm::dvec3(strand.normal));
          ASSERT_NEAR(rise, (2 * h - h * h) * 0.35, 1e-4);
          if (i > 1)
            winding += turn(side[static_cast<std::size_t>(i - 1)],
                            side[static_cast<std::size_t>(i)], glm::dvec3(strand.normal));
        }
        // omega radians per unit h, whichever way round the surface's frame winds.
        const double expected = 4 * kPi * strand.reach * (samples - 2.0) / (samples - 1.0);
        EXPECT_NEAR(std::abs(winding), expected, 1e-3 * expected);
      });
  EXPECT_GT(measured, 300u);
}

// The exports sample a strand by its curl (fur::strandSamples): on models/fur-curls' square of
// many small curls (ω = 40, six turns and more over the length) the exported strand winds as
// the shells' curl does and keeps to its path, where seven points made a gentle arc.
TEST(FurStage, ExportedStrandsFollowTheirCurl) {
  Built b;
  build(b, kModels / "fur-curls" / "curls.l", kModels / "fur-curls" / "curls.v");
  const FurPart& part = b.scene.organ<FurPart>();
  const FurSurface* curly = nullptr;
  for (const FurSurface& s : part.surfaces) {
    if (part.attributes[static_cast<std::size_t>(s.attributes)].curlFrequency == 40) curly = &s;
  }
  ASSERT_NE(curly, nullptr);
  const FurAttributes& a = part.attributes[static_cast<std::size_t>(curly->attributes)];
  const int samples = fur::strandSamples(a);
  EXPECT_GE(samples, 12 * 40 / (2 * kPi));  // twelve points a turn
  EXPECT_FALSE(fur::strandSamplesCapped(a));
  // The same strands finely sampled: the path the exported ones must keep to.
  std::vector<std::vector<glm::vec3>> fine;
  fur::forEachStrand(b.scene, *curly, 801, [&](const fur::FurStrandView& strand) {
    if (fine.size() < 200) fine.emplace_back(strand.points.begin(), strand.points.end());
  });
  auto check = [&](int points, double& worstWinding, double& worstGap) {
    std::size_t k = 0;
    worstWinding = worstGap = 0;
    fur::forEachStrand(b.scene, *curly, points, [&](const fur::FurStrandView& strand) {
      if (k >= fine.size()) return;
      const std::vector<glm::dvec3> side = across(strand);
      double winding = 0;
      for (int i = 2; i < points; ++i) {
        winding += turn(side[static_cast<std::size_t>(i - 1)], side[static_cast<std::size_t>(i)],
                        glm::dvec3(strand.normal));
      }
      const double expected = 40 * strand.reach * (points - 2.0) / (points - 1.0);
      worstWinding = std::max(worstWinding, std::abs(std::abs(winding) - expected) / expected);
      // Each fine point's distance to the exported polyline, over the strand's curl radius at
      // its tip (K_alpha L h).
      const double radius = a.curlRadius * a.length * strand.reach;
      for (const glm::vec3& f : fine[k]) {
        double nearest = 1e30;
        for (std::size_t i = 0; i + 1 < strand.points.size(); ++i) {
          const glm::dvec3 p(strand.points[i]), q(strand.points[i + 1]), x(f);
          const double t = std::clamp(glm::dot(x - p, q - p) / std::max(glm::dot(q - p, q - p), 1e-30), 0.0, 1.0);
          nearest = std::min(nearest, glm::length(x - (p + t * (q - p))));
        }
        worstGap = std::max(worstGap, nearest / radius);
      }
      ++k;
    });
  };
  double winding = 0, gap = 0;
  check(samples, winding, gap);
  RecordProperty("worst_winding_error", std::to_string(winding));
  RecordProperty("worst_gap_over_curl_radius", std::to_string(gap));
  EXPECT_LT(winding, 0.01);
  EXPECT_LT(gap, 0.06);
  // Seven points, as before: the curl is lost.
  check(7, winding, gap);
  EXPECT_GT(gap, 0.5);
  // A curl beyond what the cap follows says so.
  FurAttributes wild = a;
  wild.curlFrequency = 1e4f;
  EXPECT_EQ(fur::strandSamples(wild), fur::kMaxStrandSamples);
  EXPECT_TRUE(fur::strandSamplesCapped(wild));
  FurAttributes straight = a;
  straight.curlRadius = 0;
  EXPECT_EQ(fur::strandSamples(straight), fur::kMinStrandSamples);
}

TEST(FurStage, WetStrandsDoNotCurlAndLeanTowardsTheirClump) {
  Built b;
  buildTorus(b);
  FurSurface& s = b.scene.organ<FurPart>().surfaces[0];
  FurAttributes& fur = b.scene.organ<FurPart>().attributes[static_cast<std::size_t>(s.attributes)];
  fur.curlRadius = 0.3f;
  fur.curlFrequency = static_cast<float>(4 * kPi);
  fur::blendDroplet(s, glm::vec2(0.5f, 0.5f), 0.1f, 1.0f);
  const int samples = 17;
  std::size_t wet = 0, dry = 0;
  fur::forEachStrand(b.scene, s, samples, [&](const fur::FurStrandView& strand) {
    const glm::vec4 mask = fur::wetnessAt(s, strand.uv);
    const std::vector<glm::dvec3> side = across(strand);
    if (mask.w == 0) {
      ++dry;
      return;
    }
    const glm::vec2 fromCentre = fur::parameterDifference(s, strand.uv, glm::vec2(mask.x, mask.y));
    if (glm::length(fromCentre) < 0.02f) return;  // too near the centre to lean measurably
    ++wet;
    ASSERT_LE(glm::length(fromCentre), mask.z);  // the rim of a clump has no strands
    // No winding: every point across the normal lies on one line from the root.
    for (int i = 2; i < samples; ++i) {
      const glm::dvec3 a = side[1], c = side[static_cast<std::size_t>(i)];
      ASSERT_LT(glm::length(glm::cross(a, c)), 1e-3 * glm::length(a) * glm::length(c) + 1e-12);
      // Further along the strand, further towards the clump's centre.
      ASSERT_GE(glm::length(c), glm::length(side[static_cast<std::size_t>(i - 1)]) - 1e-7);
    }
  });
  EXPECT_GT(wet, 100u);
  EXPECT_GT(dry, 10 * wet);
}

TEST(FurStage, ViewFileDropletsLandInTheMask) {
  Built b;
  buildTorus(b, "wet.v");
  ASSERT_EQ(b.report.droplets, 5u);
  const FurSurface& s = b.scene.organ<FurPart>().surfaces[0];
  EXPECT_EQ(s.wetnessSize, 256);
  // wet.v's first droplet: (0.2, 0.1), radius 0.08, wetness 1.
  EXPECT_EQ(fur::wetnessAt(s, glm::vec2(0.2f, 0.1f)).w, 1.0f);
  EXPECT_EQ(fur::wetnessAt(s, glm::vec2(0.2f, 0.3f)).w, 0.0f);
  // Random droplets add to them, seeded.
  FurStageOptions options;
  options.droplets = 40;
  options.dropletSeed = 9;
  Built sprayed, again;
  build(sprayed, kModels / "fur-torus" / "torus.l", kModels / "fur-torus" / "torus.v", options);
  build(again, kModels / "fur-torus" / "torus.l", kModels / "fur-torus" / "torus.v", options);
  EXPECT_EQ(sprayed.report.droplets, 40u);
  EXPECT_EQ(sprayed.scene.organ<FurPart>().surfaces[0].wetness,
            again.scene.organ<FurPart>().surfaces[0].wetness);
  std::size_t wetTexels = 0;
  for (const glm::vec4& t : sprayed.scene.organ<FurPart>().surfaces[0].wetness)
    wetTexels += t.w > 0;
  EXPECT_GT(wetTexels, 0u);
}

// Fur on a mesh surface (models/mesh-body, docs/meshes.md): one fur surface of the mesh's
// triangles whose (u, v) are its file's atlas, scaled, and whose texels are square on average
// over the whole body: the atlas's scales are the root mean squares of ∂P/∂u and ∂P/∂v (a fit
// over edges followed the pinched poles and made the texels ten times wider than tall).
TEST(FurStage, FurOnAMeshFollowsItsAtlasWithSquareTexels) {
  Built b;
  build(b, kModels / "mesh-body" / "body.l", kModels / "mesh-body" / "body.v");
  ASSERT_EQ(b.scene.organSurfaces.size(), 1u);
  ASSERT_EQ(b.scene.organ<FurPart>().surfaces.size(), 1u);
  const OrganSurface& organ = b.scene.organSurfaces[0];
  EXPECT_EQ(organ.kind, OrganSurfaceKind::Mesh);
  const FurSurface& fur = b.scene.organ<FurPart>().surfaces[0];
  ASSERT_EQ(fur.uv.size(), organ.uv.size());
  EXPECT_EQ(fur.triangleCount(), 3008u);
  // The fur's (u, v) are the atlas's, each scaled and shifted (or mirrored, for a right-handed
  // frame): a line through every vertex.
  for (int axis = 0; axis < 2; ++axis) {
    double su = 0, sf = 0, suu = 0, suf = 0;
    const double n = static_cast<double>(fur.uv.size());
    for (std::size_t i = 0; i < fur.uv.size(); ++i) {
      const double u = organ.uv[i][axis], f = fur.uv[i][axis];
      su += u;
      sf += f;
      suu += u * u;
      suf += u * f;
    }
    const double slope = (n * suf - su * sf) / (n * suu - su * su);
    const double offset = (sf - slope * su) / n;
    double worst = 0;
    for (std::size_t i = 0; i < fur.uv.size(); ++i) {
      worst = std::max(worst, std::abs(offset + slope * organ.uv[i][axis] - fur.uv[i][axis]));
      EXPECT_GE(fur.uv[i][axis], -1e-5f);
      EXPECT_LE(fur.uv[i][axis], 1 + 1e-5f);
    }
    EXPECT_LT(worst, 1e-5) << "axis " << axis;
    EXPECT_NE(slope, 0) << "axis " << axis;
  }
  // Texels square on average: the root mean squares of the world lengths of a texture unit along
  // each direction, weighted by texture area, agree within 10%.
  double alongU = 0, alongV = 0, weight = 0;
  for (std::size_t t = 0; t + 2 < fur.indices.size(); t += 3) {
    const std::uint32_t a = fur.indices[t], c1 = fur.indices[t + 1], c2 = fur.indices[t + 2];
    const glm::dvec2 d1 = glm::dvec2(fur.texcoords[c1] - fur.texcoords[a]);
    const glm::dvec2 d2 = glm::dvec2(fur.texcoords[c2] - fur.texcoords[a]);
    const double det = d1.x * d2.y - d1.y * d2.x;
    if (std::abs(det) < 1e-12) continue;
    const glm::dvec3 e1 = glm::dvec3(fur.positions[c1] - fur.positions[a]);
    const glm::dvec3 e2 = glm::dvec3(fur.positions[c2] - fur.positions[a]);
    const glm::dvec3 dU = (d2.y * e1 - d1.y * e2) / det, dV = (-d2.x * e1 + d1.x * e2) / det;
    const double w = std::abs(det);
    alongU += w * glm::dot(dU, dU);
    alongV += w * glm::dot(dV, dV);
    weight += w;
  }
  ASSERT_GT(weight, 0);
  const double ratio = std::sqrt(alongU / alongV);
  std::printf("mesh fur: a texture unit is %.3f by %.3f world units\n", std::sqrt(alongU / weight),
              std::sqrt(alongV / weight));
  EXPECT_NEAR(ratio, 1, 0.1);
}

// Fur on closed meshes without texture coordinates (tests/fixtures/hairs: a torus and a bumpy
// sphere, made by scripts/make-meshes.py) grows through an atlas of charts: the strands number
// the requested density times the area, over the whole mesh and over each eighth of it (its x, y
// and z above or below the middle), within 10%; no triangle's (u, v) is mirrored (the fur's frame
// would turn over there) and no two triangles share a place of the wetness mask (one droplet
// would clump the fur in two places). Their x and y, as (u, v), laid the top over the bottom and
// made the fur 1.6 to 5 times too dense.
class FurOnClosedMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(FurOnClosedMesh, HasTheRequestedDensityEverywhere) {
  const fs::path fixtures = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "hairs";
  Built b;
  build(b, fixtures / "fur_mesh.l", fixtures / GetParam());
  ASSERT_EQ(b.scene.organ<FurPart>().surfaces.size(), 1u);
  const FurSurface& s = b.scene.organ<FurPart>().surfaces[0];
  const FurAttributes& fur =
      b.scene.organ<FurPart>().attributes[static_cast<std::size_t>(s.attributes)];
  const double texel = fur.length / b.resources.view.organ<FurSettings>().texelsPerLength;
  const double requested = fur.density / (texel * texel);  // strands per unit area
  glm::dvec3 middle(0.0);
  for (const glm::vec3& p : s.positions) middle += glm::dvec3(p);
  middle /= static_cast<double>(s.positions.size());
  const auto eighth = [&](const glm::dvec3& p) {
    return (p.x > middle.x ? 1 : 0) + (p.y > middle.y ? 2 : 0) + (p.z > middle.z ? 4 : 0);
  };
  std::array<double, 8> area{}, strands{};
  double mirrored = 0;
  for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3) {
    const std::uint32_t i = s.indices[t], j = s.indices[t + 1], k = s.indices[t + 2];
    const glm::dvec3 a(s.positions[i]), c1(s.positions[j]), c2(s.positions[k]);
    const double world = 0.5 * glm::length(glm::cross(c1 - a, c2 - a));
    area[static_cast<std::size_t>(eighth((a + c1 + c2) / 3.0))] += world;
    const glm::dvec2 d1 = glm::dvec2(s.uv[j] - s.uv[i]), d2 = glm::dvec2(s.uv[k] - s.uv[i]);
    if (d1.x * d2.y - d1.y * d2.x < 0) mirrored += world;
  }
  fur::forEachStrand(b.scene, s, 2, [&](const fur::FurStrandView& strand) {
    strands[static_cast<std::size_t>(eighth(glm::dvec3(strand.points[0])))] += 1;
  });
  double allArea = 0, allStrands = 0;
  for (std::size_t e = 0; e < 8; ++e) {
    allArea += area[e];
    allStrands += strands[e];
    if (area[e] < 0.02 * s.area) continue;
    EXPECT_NEAR(strands[e] / area[e] / requested, 1.0, 0.1) << "eighth " << e;
  }
  std::printf("%s: %.0f strands over %.2f units², %.3f of the requested density\n", GetParam(),
              allStrands, allArea, allStrands / allArea / requested);
  EXPECT_NEAR(allStrands / allArea / requested, 1.0, 0.1);
  EXPECT_LT(mirrored, 1e-3 * allArea);
  // The wetness mask's texels (512² here) that more than one triangle covers: none but along
  // shared edges.
  constexpr int kGrid = 512;
  std::vector<std::uint8_t> covered(kGrid * kGrid, 0);
  std::size_t twice = 0, once = 0;
  for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3) {
    const glm::dvec2 a(s.uv[s.indices[t]]), c1(s.uv[s.indices[t + 1]]), c2(s.uv[s.indices[t + 2]]);
    const double det = (c1.x - a.x) * (c2.y - a.y) - (c2.x - a.x) * (c1.y - a.y);
    if (std::abs(det) < 1e-14) continue;
    const glm::dvec2 low = glm::min(a, glm::min(c1, c2)) * double(kGrid);
    const glm::dvec2 high = glm::max(a, glm::max(c1, c2)) * double(kGrid);
    for (int y = std::max(0, int(low.y)); y <= std::min(kGrid - 1, int(high.y)); ++y)
      for (int x = std::max(0, int(low.x)); x <= std::min(kGrid - 1, int(high.x)); ++x) {
        const glm::dvec2 p = (glm::dvec2(x, y) + 0.5) / double(kGrid);
        const double u = ((c1.x - p.x) * (c2.y - p.y) - (c2.x - p.x) * (c1.y - p.y)) / det;
        const double v = ((c2.x - p.x) * (a.y - p.y) - (a.x - p.x) * (c2.y - p.y)) / det;
        if (u < 0 || v < 0 || u + v > 1) continue;
        std::uint8_t& n = covered[static_cast<std::size_t>(y) * kGrid + x];
        if (n == 1) ++twice;
        if (n == 0) ++once;
        n = static_cast<std::uint8_t>(std::min(n + 1, 2));
      }
  }
  EXPECT_GT(once, 0u);
  EXPECT_LT(static_cast<double>(twice), 0.005 * static_cast<double>(once));
}

INSTANTIATE_TEST_SUITE_P(
    UvLessMeshes, FurOnClosedMesh, ::testing::Values("fur_torus.v", "fur_bumpy_sphere.v"),
    [](const auto& info) {
      return std::string(info.param).substr(4, std::string(info.param).size() - 6);
    });

}  // namespace
}  // namespace hirsute
