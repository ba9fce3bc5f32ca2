#include "hirsute/viewer/interaction/mouse_camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace hirsute {
namespace {

constexpr float kMinZoom = 1e-3f, kMaxZoom = 1e4f;

glm::quat about(float degrees, const glm::vec3& axis) {
  return glm::angleAxis(glm::radians(degrees), axis);
}

}  // namespace

void MouseCamera::rotate(float aboutVertical, float aboutHorizontal) {
  // New turns are about the screen's axes as they are now: applied after what was there.
  orientation_ = glm::normalize(about(aboutHorizontal, {1, 0, 0}) *
                                about(aboutVertical, {0, 1, 0}) * orientation_);
}

void MouseCamera::roll(float degrees) {
  // Clockwise on the screen is negative about the axis towards the viewer.
  orientation_ = glm::normalize(about(-degrees, {0, 0, 1}) * orientation_);
}

void MouseCamera::zoom(float factor) {
  if (!(factor > 0) || !std::isfinite(factor)) return;
  zoom_ = std::clamp(zoom_ * factor, kMinZoom, kMaxZoom);
}

void MouseCamera::pan(float right, float up) {
  // Stored in the fitted window's units, so that zooming keeps the point in the middle fixed.
  pan_ += glm::vec2(right, up) / zoom_;
}

void MouseCamera::reset() {
  *this = MouseCamera();
}

void MouseCamera::dragRotate(glm::vec2 pixels) {
  rotate(pixels.x * kDegreesPerPixel, pixels.y * kDegreesPerPixel);
}

void MouseCamera::dragPan(glm::vec2 pixels, int windowHeight) {
  float h = static_cast<float>(std::max(windowHeight, 1));
  pan(pixels.x / h, -pixels.y / h);  // window y runs down
}

void MouseCamera::dragZoom(glm::vec2 pixels) {
  zoom(std::exp(-pixels.y * kZoomPerPixel));  // moving up (negative y) zooms in
}

void MouseCamera::dragRoll(glm::vec2 pixels) {
  roll(pixels.x * kDegreesPerPixel);
}

void MouseCamera::wheel(float steps) {
  zoom(std::pow(kZoomPerWheelStep, steps));
}

bool MouseCamera::isIdentity() const {
  return orientation_ == glm::quat(1, 0, 0, 0) && zoom_ == 1 && pan_ == glm::vec2(0);
}

Camera MouseCamera::apply(const Camera& fitted, const Bounds& plant) const {
  if (isIdentity()) return fitted;
  Camera c = fitted;
  // The plant turns by the orientation in the fitted eye frame (columns: right, up, towards the
  // viewer); the camera turns the other way about the point looked at.
  glm::mat3 eyeToWorld(fitted.right, fitted.up, -fitted.forward);
  glm::quat inverse = glm::inverse(orientation_);
  c.right = glm::normalize(eyeToWorld * (inverse * glm::vec3(1, 0, 0)));
  c.up = glm::normalize(eyeToWorld * (inverse * glm::vec3(0, 1, 0)));
  c.forward = glm::normalize(eyeToWorld * (inverse * glm::vec3(0, 0, -1)));

  float distance = glm::distance(fitted.eye, fitted.target);
  float windowHeight;  // world units, at the point looked at, after zooming
  if (c.projection == Projection::Perspective) {
    distance /= zoom_;
    windowHeight = 2 * distance * std::tan(glm::radians(c.fieldOfViewY) / 2);
  } else {
    c.halfWidth = fitted.halfWidth / zoom_;
    c.halfHeight = fitted.halfHeight / zoom_;
    windowHeight = 2 * fitted.halfHeight;
  }
  if (c.projection == Projection::Perspective) windowHeight *= zoom_;  // pan is in fitted units
  glm::vec3 shift = (c.right * pan_.x + c.up * pan_.y) * windowHeight;
  c.target = fitted.target - shift;
  c.eye = c.target - c.forward * distance;

  // Clip to the plant's bounding sphere, as fitCamera does.
  glm::vec3 center = plant.empty() ? c.target : plant.center();
  float radius = 0;
  if (!plant.empty()) {
    for (int i = 0; i < 8; ++i) {
      glm::vec3 corner{(i & 1) ? plant.max.x : plant.min.x, (i & 2) ? plant.max.y : plant.min.y,
                       (i & 4) ? plant.max.z : plant.min.z};
      radius = std::max(radius, glm::length(corner - center));
    }
  }
  float along = glm::dot(center - c.eye, c.forward);
  float margin = radius * 1e-3f + 1e-6f;
  c.nearPlane = along - radius - margin;
  c.farPlane = along + radius + margin;
  if (c.projection == Projection::Perspective) {
    c.nearPlane = std::max(c.nearPlane, std::max(c.farPlane * 1e-4f, 1e-6f));
    if (c.farPlane <= c.nearPlane) c.farPlane = c.nearPlane * 2;
  }
  float aspect = static_cast<float>(c.viewport.x) / static_cast<float>(c.viewport.y);
  c.view = glm::lookAt(c.eye, c.target, c.up);
  c.projectionMatrix =
      c.projection == Projection::Perspective
          ? glm::perspective(glm::radians(c.fieldOfViewY), aspect, c.nearPlane, c.farPlane)
          : glm::ortho(-c.halfWidth, c.halfWidth, -c.halfHeight, c.halfHeight, c.nearPlane,
                       c.farPlane);
  return c;
}

}  // namespace hirsute
