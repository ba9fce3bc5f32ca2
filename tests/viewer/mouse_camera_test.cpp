// The viewer's mouse camera: cpfg's drags turned into camera motion, checked where points land
// on the screen.
#include "hirsute/viewer/interaction/mouse_camera.h"

#include <gtest/gtest.h>

namespace hirsute {
namespace {

// A plant 2 units tall standing at the origin, seen from the front (cpfg's default view).
struct Fixture {
  ViewSettings view;
  Bounds plant;
  Camera fitted;
  Fixture() {
    plant.add({-0.5f, 0, -0.5f});
    plant.add({0.5f, 2, 0.5f});
    fitted = fitCamera(view, plant, {400, 400});
  }
};

TEST(MouseCameraTest, UntouchedIsTheFittedCamera) {
  Fixture f;
  MouseCamera mouse;
  EXPECT_TRUE(mouse.isIdentity());
  Camera c = mouse.apply(f.fitted, f.plant);
  EXPECT_EQ(c.viewProjection(), f.fitted.viewProjection());
}

TEST(MouseCameraTest, RotatingAboutTheVerticalTurnsTheFrontToTheRight) {
  Fixture f;
  MouseCamera mouse;
  mouse.rotate(90, 0);
  Camera c = mouse.apply(f.fitted, f.plant);
  // A point in front of the plant's axis (towards the viewer, +z) moves to the right of it.
  glm::vec3 axis = c.toPixels({0, 1, 0});
  glm::vec3 front = c.toPixels({0, 1, 0.5f});
  EXPECT_GT(front.x, axis.x + 10);
  EXPECT_NEAR(front.y, axis.y, 0.5f);
  // The target stays in the middle of the window.
  EXPECT_NEAR(axis.x, 200, 0.5f);
}

TEST(MouseCameraTest, DraggingDownTipsTheTopTowardsTheViewer) {
  Fixture f;
  MouseCamera mouse;
  mouse.dragRotate({0, 90 / MouseCamera::kDegreesPerPixel});
  Camera c = mouse.apply(f.fitted, f.plant);
  // Seen from above after a quarter turn: the top is nearer the eye than the base.
  float topDepth = c.toPixels({0, 2, 0}).z, baseDepth = c.toPixels({0, 0, 0}).z;
  EXPECT_LT(topDepth, baseDepth);
  // Both still inside the clipping range.
  EXPECT_GT(topDepth, 0);
  EXPECT_LT(baseDepth, 1);
}

TEST(MouseCameraTest, ZoomMagnifiesAboutTheMiddle) {
  Fixture f;
  MouseCamera mouse;
  float before = f.fitted.toPixels({0.5f, 1, 0}).x - 200;
  mouse.zoom(2);
  Camera c = mouse.apply(f.fitted, f.plant);
  EXPECT_NEAR(c.toPixels({0.5f, 1, 0}).x - 200, 2 * before, 0.5f);
  EXPECT_NEAR(c.toPixels({0, 1, 0}).x, 200, 0.5f);
}

TEST(MouseCameraTest, MiddleDragUpAndWheelForwardZoomIn) {
  MouseCamera drag, wheel;
  drag.dragZoom({0, -50});
  wheel.wheel(2);
  EXPECT_GT(drag.zoomFactor(), 1);
  EXPECT_NEAR(wheel.zoomFactor(), 1.21f, 1e-4f);
}

TEST(MouseCameraTest, PanFollowsTheMouseAtAnyZoom) {
  Fixture f;
  for (float zoom : {1.0f, 3.0f}) {
    MouseCamera mouse;
    mouse.zoom(zoom);
    // Dragging 40 pixels right and 20 down moves the plant as far on the screen.
    mouse.dragPan({40, 20}, 400);
    Camera c = mouse.apply(f.fitted, f.plant);
    Camera still = [&] {
      MouseCamera z;
      z.zoom(zoom);
      return z.apply(f.fitted, f.plant);
    }();
    glm::vec3 moved = c.toPixels({0.2f, 1.3f, 0}), before = still.toPixels({0.2f, 1.3f, 0});
    EXPECT_NEAR(moved.x - before.x, 40, 0.5f) << "zoom " << zoom;
    EXPECT_NEAR(moved.y - before.y, 20, 0.5f) << "zoom " << zoom;
  }
}

TEST(MouseCameraTest, RollTurnsTheImageClockwise) {
  Fixture f;
  MouseCamera mouse;
  mouse.roll(90);
  Camera c = mouse.apply(f.fitted, f.plant);
  // The top of the plant, above the middle before, is to the right of it after a clockwise turn.
  glm::vec3 middle = c.toPixels({0, 1, 0}), top = c.toPixels({0, 2, 0});
  EXPECT_GT(top.x, middle.x + 10);
  EXPECT_NEAR(top.y, middle.y, 0.5f);
}

TEST(MouseCameraTest, PerspectiveZoomMovesTheEyeCloser) {
  Fixture f;
  f.view.projection = Projection::Perspective;
  f.view.viewpoint = {0, 1, 10};
  f.view.viewReference = {0, 1, 0};
  Camera fitted = fitCamera(f.view, f.plant, {400, 400});
  MouseCamera mouse;
  mouse.zoom(2);
  Camera c = mouse.apply(fitted, f.plant);
  EXPECT_NEAR(glm::distance(c.eye, c.target), glm::distance(fitted.eye, fitted.target) / 2, 1e-4f);
  EXPECT_GT(c.nearPlane, 0);
}

TEST(MouseCameraTest, ResetForgetsEverything) {
  MouseCamera mouse;
  mouse.rotate(10, 20);
  mouse.pan(0.1f, 0.2f);
  mouse.zoom(3);
  mouse.reset();
  EXPECT_TRUE(mouse.isIdentity());
}

}  // namespace
}  // namespace hirsute
