// The display transform of the traced picture: the exposure scales linear light by 2^EV, the
// filmic curve starts at black, rises monotonically and rolls highlights off towards white
// instead of clipping them at 1; `none` is the picture as it always was.
#include "hirsute/viewer/trace/tone_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "hirsute/viewer/trace/path_tracer.h"

namespace hirsute::trace {
namespace {

TEST(ToneCurve, FilmicMapsBlackToBlackAndRisesMonotonically) {
  EXPECT_EQ(toneMap(0.0f, ToneCurve::Filmic), 0.0f);
  float previous = 0;
  for (int i = 1; i <= 4000; ++i) {
    const float x = 0.005f * static_cast<float>(i);
    const float y = toneMap(x, ToneCurve::Filmic);
    EXPECT_GE(y, previous) << x;
    previous = y;
  }
}

TEST(ToneCurve, FilmicRollsHighlightsOffBelowWhite) {
  // Where `none` clips, the filmic curve still tells 1, 2 and 4 apart, each below white.
  const float one = toneMap(1, ToneCurve::Filmic), two = toneMap(2, ToneCurve::Filmic),
              four = toneMap(4, ToneCurve::Filmic);
  EXPECT_LT(one, two);
  EXPECT_LT(two, four);
  EXPECT_LT(four, 1.0f);
  EXPECT_EQ(toneMap(2, ToneCurve::None), toneMap(4, ToneCurve::None));
  EXPECT_EQ(toneMap(100, ToneCurve::Filmic), 1.0f);
  EXPECT_EQ(toneMap(std::numeric_limits<float>::infinity(), ToneCurve::Filmic), 1.0f);
  EXPECT_EQ(toneMap(std::numeric_limits<float>::quiet_NaN(), ToneCurve::Filmic), 0.0f);
  EXPECT_EQ(toneMap(-1, ToneCurve::Filmic), 0.0f);
}

TEST(ToneCurve, NoneIsTheStraightLineClampedAtWhite) {
  EXPECT_EQ(toneMap(0.25f, ToneCurve::None), 0.25f);
  EXPECT_EQ(toneMap(3, ToneCurve::None), 1.0f);
  EXPECT_EQ(toneMap(-1, ToneCurve::None), 0.0f);
}

TEST(ToneCurve, ExposureScalesLinearLightByPowersOfTwo) {
  DisplayTransform transform;
  transform.exposure = 2;
  EXPECT_FLOAT_EQ(displayLight(glm::vec3(0.1f, 0.2f, 0.05f), transform).g, 0.8f);
  transform.exposure = -1;
  EXPECT_FLOAT_EQ(displayLight(glm::vec3(0.5f), transform).r, 0.25f);
  transform.tone = ToneCurve::Filmic;
  EXPECT_FLOAT_EQ(displayLight(glm::vec3(4.0f), transform).b, toneMap(2, ToneCurve::Filmic));
}

TEST(ToneCurve, TheDisplayImageIsExposedAndTonedAndUnchangedByDefault) {
  TraceImage image;
  image.width = 3;
  image.height = 1;
  image.radiance = {glm::vec3(0.25f), glm::vec3(2.0f), glm::vec3(4.0f)};
  image.samples = {1, 1, 1};
  const RgbaImage plain = displayImage(image);
  EXPECT_EQ(plain.pixel(0, 0).r, static_cast<int>(std::lround(displayLevel(0.25f))));
  EXPECT_EQ(plain.pixel(1, 0).r, 255);
  EXPECT_EQ(plain.pixel(2, 0).r, 255);
  DisplayTransform transform;
  transform.exposure = 1;
  EXPECT_EQ(displayImage(image, transform).pixel(0, 0).g,
            static_cast<int>(std::lround(displayLevel(0.5f))));
  transform.exposure = 0;
  transform.tone = ToneCurve::Filmic;
  const RgbaImage filmic = displayImage(image, transform);
  EXPECT_LT(filmic.pixel(1, 0).r, filmic.pixel(2, 0).r);  // the highlights are told apart
  EXPECT_LT(filmic.pixel(2, 0).r, 255);
}

TEST(ToneCurve, TheBackgroundIsTracedAsTheRadianceShownAsItsColour) {
  // The view's background colour looks the same under any exposure and curve.
  for (const ToneCurve tone : {ToneCurve::None, ToneCurve::Filmic}) {
    for (const float exposure : {-2.0f, 0.0f, 1.5f}) {
      const DisplayTransform transform{exposure, tone};
      for (const float light : {0.0f, 0.01f, 0.2f, 0.5f, 0.9f, 1.0f}) {
        const glm::vec3 radiance = radianceShownAs(glm::vec3(light), transform);
        EXPECT_NEAR(displayLight(radiance, transform).g, light, 1e-5f) << exposure << " " << light;
      }
    }
  }
}

TEST(ToneCurve, CurvesAreNamed) {
  EXPECT_EQ(toneCurveNamed("none"), ToneCurve::None);
  EXPECT_EQ(toneCurveNamed("filmic"), ToneCurve::Filmic);
  EXPECT_FALSE(toneCurveNamed("aces").has_value());
}

}  // namespace
}  // namespace hirsute::trace
