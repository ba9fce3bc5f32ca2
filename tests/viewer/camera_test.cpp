// cpfg's camera: fitting in parallel projection, the eye in perspective, twist.
#include "hirsute/viewer/view/camera.h"

#include <gtest/gtest.h>

namespace hirsute {
namespace {

Bounds box(glm::vec3 min, glm::vec3 max) {
  Bounds b;
  b.add(min);
  b.add(max);
  return b;
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(CameraTest, ParallelFitCentresTheBoundingBox) {
  ViewSettings view;
  Camera camera = fitCamera(view, box({2, 10, -1}, {6, 30, 1}), {300, 200});
  expectNear(camera.toPixels({4, 20, 0}), {150, 100, 0.5f}, 1e-3f);
  expectNear(camera.target, {4, 20, 0}, 1e-5f);
}

TEST(CameraTest, ParallelFitFillsTheLimitingSide) {
  ViewSettings view;
  // A tall box in a wide image: its height fills the image, top edge at row 0.
  Camera camera = fitCamera(view, box({0, 0, 0}, {1, 4, 0}), {400, 200});
  EXPECT_NEAR(camera.toPixels({0.5f, 4, 0}).y, 0, 1e-3);
  EXPECT_NEAR(camera.toPixels({0.5f, 0, 0}).y, 200, 1e-3);
  EXPECT_NEAR(camera.toPixels({1, 2, 0}).x - camera.toPixels({0, 2, 0}).x, 50, 1e-3);
  // A wide box: its width fills the image.
  camera = fitCamera(view, box({0, 0, 0}, {10, 1, 0}), {400, 200});
  EXPECT_NEAR(camera.toPixels({0, 0.5f, 0}).x, 0, 1e-3);
  EXPECT_NEAR(camera.toPixels({10, 0.5f, 0}).x, 400, 1e-3);
}

TEST(CameraTest, ScaleFactorShrinksThePlantInTheWindow) {
  ViewSettings view;
  view.scaleFactor = 0.5f;
  Camera camera = fitCamera(view, box({0, 0, 0}, {1, 4, 0}), {400, 200});
  EXPECT_NEAR(camera.toPixels({0.5f, 4, 0}).y, 50, 1e-3);
  EXPECT_NEAR(camera.toPixels({0.5f, 0, 0}).y, 150, 1e-3);
  view.scaleFactor = 0;  // cpfg: 0 means 1
  camera = fitCamera(view, box({0, 0, 0}, {1, 4, 0}), {400, 200});
  EXPECT_NEAR(camera.toPixels({0.5f, 4, 0}).y, 0, 1e-3);
}

TEST(CameraTest, ParallelFitHoldsTheProjectedCornersOfAnObliqueView) {
  ViewSettings view;
  view.viewpoint = {1, 1, 1};
  Bounds plant = box({-1, -1, -1}, {1, 1, 1});
  Camera camera = fitCamera(view, plant, {256, 256});
  float minX = 1e9f, maxX = -1e9f, minY = 1e9f, maxY = -1e9f;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    glm::vec3 p = camera.toPixels(c);
    minX = std::min(minX, p.x);
    maxX = std::max(maxX, p.x);
    minY = std::min(minY, p.y);
    maxY = std::max(maxY, p.y);
    EXPECT_GT(p.z, 0.0f);
    EXPECT_LT(p.z, 1.0f);
  }
  // The cube's outline touches two opposite sides of the square image and stays inside.
  EXPECT_GE(minX, -1e-3f);
  EXPECT_LE(maxX, 256 + 1e-3f);
  EXPECT_GE(minY, -1e-3f);
  EXPECT_LE(maxY, 256 + 1e-3f);
  EXPECT_NEAR(std::max(maxX - minX, maxY - minY), 256, 1e-2);
}

TEST(CameraTest, BoxReplacesThePlantsBoundsInParallelProjection) {
  ViewSettings view;
  view.box = box({-10, -10, -1}, {10, 10, 1});
  Camera camera = fitCamera(view, box({0, 0, 0}, {1, 1, 0}), {200, 200});
  expectNear(camera.toPixels({0, 0, 0}), {100, 100, camera.toPixels({0, 0, 0}).z}, 1e-3f);
  EXPECT_NEAR(camera.toPixels({1, 0, 0}).x, 110, 1e-3);
}

TEST(CameraTest, LineOfSightRunsFromViewpointToReferencePoint) {
  ViewSettings view;
  view.viewpoint = {5, 0, 0};  // looking along -x: +z is to the left, +y up
  Camera camera = fitCamera(view, box({-1, -1, -1}, {1, 1, 1}), {200, 200});
  expectNear(camera.forward, {-1, 0, 0}, 1e-6f);
  EXPECT_LT(camera.toPixels({0, 0, 1}).x, 100);
  EXPECT_LT(camera.toPixels({0, 1, 0}).y, 100);
  // Nearer points get smaller depths.
  EXPECT_LT(camera.toPixels({1, 0, 0}).z, camera.toPixels({-1, 0, 0}).z);
}

TEST(CameraTest, TwistTurnsTheImageClockwise) {
  ViewSettings view;
  view.twistDegrees = 90;
  Camera camera = fitCamera(view, box({-1, -1, 0}, {1, 1, 0}), {200, 200});
  // World up now points to the right of the image.
  glm::vec3 above = camera.toPixels({0, 1, 0});
  EXPECT_NEAR(above.x, 200, 1e-3);
  EXPECT_NEAR(above.y, 100, 1e-3);
}

TEST(CameraTest, LookingStraightDownHasAnUpDirection) {
  ViewSettings view;
  view.viewpoint = {0, 10, 0};
  Camera camera = fitCamera(view, box({-1, 0, -1}, {1, 0, 1}), {200, 200});
  expectNear(camera.up, {0, 0, -1}, 1e-6f);
  EXPECT_LT(camera.toPixels({0, 0, -1}).y, 100);
}

// cpfg's rayshade output for the corpus model cpfg-BackgroundScene (viewpoint 0,3,7, reference
// 0,2,0, scale factor 0.6, viewing angle 30): eyep 0 3.666667 11.666666, up 0 0.989949 -0.141421.
TEST(CameraTest, PerspectiveEyeMovesWithTheScaleFactorAsCpfg) {
  ViewSettings view;
  view.projection = Projection::Perspective;
  view.viewpoint = {0, 3, 7};
  view.viewReference = {0, 2, 0};
  view.scaleFactor = 0.6f;
  view.viewingAngle = 30;
  view.frontDistance = 0.01f;
  view.backDistance = 200;
  Camera camera = fitCamera(view, box({-1, 0, -1}, {1, 3, 1}), {320, 240});
  expectNear(camera.eye, {0, 3.666667f, 11.666666f}, 1e-4f);
  expectNear(camera.up, {0, 0.989949f, -0.141421f}, 1e-5f);
  EXPECT_FLOAT_EQ(camera.fieldOfViewY, 30);
  // The reference point is in the middle of the image; no fitting moves it.
  expectNear(camera.toPixels({0, 2, 0}), {160, 120, camera.toPixels({0, 2, 0}).z}, 1e-3f);
  // Clipping planes hold the plant and stay within front and back distance.
  EXPECT_GE(camera.nearPlane, 0.01f);
  EXPECT_LE(camera.farPlane, 200.0f);
  for (glm::vec3 c : {glm::vec3(-1, 0, -1), glm::vec3(1, 3, 1)}) {
    float z = camera.toPixels(c).z;
    EXPECT_GT(z, 0.0f);
    EXPECT_LT(z, 1.0f);
  }
}

TEST(CameraTest, PerspectiveViewingAngleIsVertical) {
  ViewSettings view;
  view.projection = Projection::Perspective;
  view.viewpoint = {0, 0, 10};
  view.viewingAngle = 90;  // half height at distance 10 is 10
  Camera camera = fitCamera(view, box({-1, -1, -1}, {1, 1, 1}), {400, 200});
  EXPECT_NEAR(camera.toPixels({0, 10, 0}).y, 0, 1e-2);
  EXPECT_NEAR(camera.toPixels({20, 0, 0}).x, 400, 1e-2);
}

TEST(CameraTest, APixelWidensWithDepthInPerspectiveAndNotInParallel) {
  ViewSettings view;
  view.projection = Projection::Perspective;
  const Camera camera = fitCamera(view, box({-1, -1, -1}, {1, 1, 1}), {200, 100});
  const float atTarget = camera.pixelSize();
  EXPECT_NEAR(camera.pixelSizeAt(camera.target), atTarget, 1e-6f * atTarget);
  const glm::vec3 twice = camera.eye + 2.0f * (camera.target - camera.eye);
  EXPECT_NEAR(camera.pixelSizeAt(twice), 2 * atTarget, 1e-5f * atTarget);
  EXPECT_EQ(camera.pixelSizeAt(camera.eye - camera.forward), 0.0f);  // behind the eye
  view.projection = Projection::Parallel;
  const Camera flat = fitCamera(view, box({-1, -1, -1}, {1, 1, 1}), {200, 100});
  EXPECT_EQ(flat.pixelSizeAt(flat.eye + 10.0f * flat.forward), flat.pixelSize());
}

TEST(CameraTest, PerspectiveWithFrontDistanceBelowZeroStillSeesThePlant) {
  ViewSettings view;  // cpfg-ArticulatedLamp: perspective with front distance -100
  view.projection = Projection::Perspective;
  view.viewpoint = {0, 0.1f, 10};
  view.viewReference = {0.5f, 1, 0};
  view.scaleFactor = 2;
  view.frontDistance = -100;
  view.backDistance = 100;
  Camera camera = fitCamera(view, box({-1, 0, -1}, {2, 1.86f, 1}), {320, 240});
  expectNear(camera.eye, {0.25f, 0.55f, 5}, 1e-5f);
  EXPECT_GT(camera.nearPlane, 0.0f);
  float z = camera.toPixels({0.5f, 1, 0}).z;
  EXPECT_GT(z, 0.0f);
  EXPECT_LT(z, 1.0f);
}

TEST(CameraTest, EmptyPlantGivesAUsableCamera) {
  ViewSettings view;
  Camera camera = fitCamera(view, Bounds{}, {100, 100});
  expectNear(camera.toPixels({0, 0, 0}), {50, 50, camera.toPixels({0, 0, 0}).z}, 1e-3f);
  EXPECT_GT(camera.halfWidth, 0.0f);
}

}  // namespace
}  // namespace hirsute
