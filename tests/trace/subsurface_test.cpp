// Random-walk subsurface scattering in a thin sheet (subsurface.h): what enters leaves when
// nothing is absorbed, the light passed through without scattering is the slab's analytic
// share, the share passed through grows with the mean free path, and the integrator's sheet
// conserves energy in a furnace.
#include "hirsute/viewer/trace/subsurface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "hirsute/viewer/trace/path_tracer.h"
#include "hirsute/viewer/trace/trace_scene.h"

namespace {

using namespace hirsute;
using namespace hirsute::trace;

struct Shares {
  double reflected = 0, transmitted = 0;
  int limited = 0;  // walks that reached the step limit
};

Shares walk(float meanFreePath, float thickness, float albedo, int walks, std::uint64_t seed) {
  SubsurfaceMaterial m;
  m.meanFreePath = meanFreePath;
  m.thickness = thickness;
  m.albedo = glm::vec3(albedo);
  Random random(seed, 1);
  Shares s;
  for (int i = 0; i < walks; ++i) {
    const SlabWalk w = walkThroughSlab(m, random);
    (w.transmitted ? s.transmitted : s.reflected) += w.weight.g;
    if (w.steps >= kMaxWalkSteps) ++s.limited;
  }
  s.reflected /= walks;
  s.transmitted /= walks;
  return s;
}

TEST(Subsurface, WithoutAbsorptionWhatEntersLeaves) {
  for (const float mfp : {0.02f, 0.1f, 0.5f, 3.0f}) {
    const Shares s = walk(mfp, 1, 1, 20000, 1);
    EXPECT_NEAR(s.reflected + s.transmitted, 1.0, 1e-3) << "mean free path " << mfp;
    EXPECT_LE(s.limited, 20) << "mean free path " << mfp;
  }
}

// Light entering diffusely (density 2μ) crosses a slab τ free paths thick unscattered with
// probability ∫ 2μ e^(−τ/μ) dμ = 2 E₃(τ); with an albedo of 0 that is all that passes.
TEST(Subsurface, UnscatteredLightIsTheSlabsAnalyticShare) {
  for (const float tau : {0.2f, 1.0f, 2.5f}) {
    double exact = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double mu = (i + 0.5) / n;
      exact += 2 * mu * std::exp(-tau / mu) / n;
    }
    const Shares s = walk(1.0f / tau, 1, 0, 200000, 2);
    EXPECT_NEAR(s.transmitted, exact, 4 * std::sqrt(exact * (1 - exact) / 200000) + 1e-4) << tau;
    EXPECT_EQ(s.reflected, 0.0) << tau;
  }
}

TEST(Subsurface, TheShareThroughGrowsWithTheMeanFreePath) {
  double previous = 0;
  for (const float mfp : {0.03f, 0.1f, 0.3f, 1.0f, 3.0f}) {
    const Shares s = walk(mfp, 1, 0.9f, 40000, 3);
    std::printf("mean free path %.2f: reflected %.4f, passed %.4f\n", mfp, s.reflected,
                s.transmitted);
    EXPECT_GT(s.transmitted, 1.3 * previous) << "mean free path " << mfp;
    previous = s.transmitted;
  }
  // And absorption takes its share: less comes out with a lower albedo.
  const Shares lossless = walk(0.2f, 1, 1, 40000, 4), absorbing = walk(0.2f, 1, 0.8f, 40000, 4);
  EXPECT_LT(absorbing.reflected + absorbing.transmitted,
            0.9 * (lossless.reflected + lossless.transmitted));
}

TEST(Subsurface, TheSingleScatteringAlbedoKeepsTheColoursOrder) {
  const glm::vec3 a = singleScatteringAlbedo(glm::vec3(0.1f, 0.5f, 0.9f));
  EXPECT_LT(a.r, a.g);
  EXPECT_LT(a.g, a.b);
  EXPECT_NEAR(singleScatteringAlbedo(glm::vec3(1.0f)).g, 1.0f, 1e-4f);
  EXPECT_NEAR(singleScatteringAlbedo(glm::vec3(0.0f)).g, 0.0f, 1e-4f);
  // A thick sheet of the albedo looks about the colour it was made from (the fit is the
  // half-space's, within a few per cent).
  const Shares thick = walk(0.01f, 1, singleScatteringAlbedo(glm::vec3(0.5f)).g, 20000, 5);
  EXPECT_NEAR(thick.reflected, 0.5, 0.05);
}

// A square sheet facing +z under a uniform sky all round: with an albedo of 1 and no specular
// lobe, the light its walks return matches the sky's, seen from either side.
TEST(Subsurface, ASheetInAFurnaceReturnsTheSkysLight) {
  TraceScene scene(TraceSettings{});
  TraceMaterial m;
  m.surface.reflectance = glm::vec3(0.5f);
  m.surface.transmittance = glm::vec3(0.5f);
  m.subsurface.meanFreePath = 0.2f;
  m.subsurface.thickness = 1;
  m.subsurface.albedo = glm::vec3(1.0f);
  TriangleBuffers b = scene.addTriangles(4, 2, scene.addMaterial(m), true, false);
  const glm::vec3 corners[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  for (int k = 0; k < 4; ++k) {
    b.positions[k] = corners[k];
    b.normals[k] = glm::vec3(0, 0, 1);
  }
  const std::uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
  for (int k = 0; k < 6; ++k) b.indices[k] = indices[k];
  scene.commit();
  TraceLights lights;
  lights.environment = std::make_shared<EnvironmentMap>(
      8, 4, std::vector<glm::vec3>(32, glm::vec3(1.0f)), glm::vec3(0, 1, 0));
  TraceOptions options;
  for (const float side : {1.0f, -1.0f}) {
    double sum = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      Random random(9, static_cast<std::uint64_t>(i));
      sum += traceRay(scene, lights, glm::vec3(0.1f, 0.2f, 3 * side), glm::vec3(0, 0, -side),
                      random, options)
                 .g;
    }
    EXPECT_NEAR(sum / n, 1.0, 0.01) << "side " << side;
  }
}

}  // namespace
