// The viewer's mouse camera: what the user does to the camera cpfg fits (camera.h) by dragging,
// kept apart from the fitted camera so that a re-derived plant keeps the user's view
// (cpfg-manual §1.3.1, "View manipulation"). Pure maths, no window: unit-tested on its own.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

class MouseCamera {
 public:
  // Degrees of rotation per pixel of mouse motion, and zoom per pixel (cpfg's feel: a drag across
  // a 600-pixel window turns the plant about half a turn).
  static constexpr float kDegreesPerPixel = 0.3f;
  static constexpr float kZoomPerPixel = 0.005f;
  static constexpr float kZoomPerWheelStep = 1.1f;

  // Turns the plant about the screen's vertical axis by `aboutVertical` degrees (a positive angle
  // turns its front to the right, as dragging the mouse right does) and about the screen's
  // horizontal axis by `aboutHorizontal` degrees (positive tips its top towards the viewer, as
  // dragging down does). Both axes run through the point looked at.
  void rotate(float aboutVertical, float aboutHorizontal);
  // Rolls the plant clockwise about the line of sight by `degrees` (cpfg: shift + middle drag).
  void roll(float degrees);
  // Magnifies by `factor` (> 1 zooms in).
  void zoom(float factor);
  // Moves the plant right and up by the given fractions of the window's height.
  void pan(float right, float up);
  // Back to the fitted camera.
  void reset();

  // Mouse motion in pixels to the actions above: rotate (left drag), pan (right drag, or left
  // drag with shift), zoom (middle drag: up zooms in), roll (middle drag with shift).
  void dragRotate(glm::vec2 pixels);
  void dragPan(glm::vec2 pixels, int windowHeight);
  void dragZoom(glm::vec2 pixels);
  void dragRoll(glm::vec2 pixels);
  void wheel(float steps);

  // The fitted camera with the user's changes: the eye orbits the point looked at, the window
  // (parallel) shrinks or the eye moves closer (perspective) by the zoom, both move by the pan,
  // and the clipping planes are drawn to the plant's bounding sphere again.
  Camera apply(const Camera& fitted, const Bounds& plant) const;

  bool isIdentity() const;
  float zoomFactor() const { return zoom_; }
  const glm::quat& orientation() const { return orientation_; }

 private:
  // The rotation of the plant in the fitted camera's eye frame (x right, y up, z towards the
  // viewer), about the point looked at.
  glm::quat orientation_{1, 0, 0, 0};
  float zoom_ = 1;
  glm::vec2 pan_{0};  // fractions of the window's height
};

}  // namespace hirsute
