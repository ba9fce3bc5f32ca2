#include "hirsute/viewer/view/camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <utility>

namespace hirsute {
namespace {

std::array<glm::vec3, 8> corners(const Bounds& b) {
  std::array<glm::vec3, 8> c;
  for (int i = 0; i < 8; ++i) {
    c[i] = {(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z};
  }
  return c;
}

float boundingRadius(const Bounds& b, const glm::vec3& center) {
  if (b.empty()) return 0;
  float r = 0;
  for (const glm::vec3& c : corners(b)) r = std::max(r, glm::length(c - center));
  return r;
}

// The screen's up direction: world +y seen along the line of sight (gluLookAt's up vector
// (0,1,0), as cpfg sets it), turned by `twist:`. Following IRIS GL's lookat, from which cpfg's
// view descends, a positive twist turns the eye counter-clockwise about the line of sight, so the
// image turns clockwise.
glm::vec3 screenUp(const glm::vec3& forward, float twistDegrees) {
  glm::vec3 up = glm::vec3(0, 1, 0) - forward * forward.y;
  if (glm::length(up) < 1e-6f) {
    // Looking straight down (or up) the y axis, world y gives no up direction: take the far
    // side of the default view (−z) as the top of the image when looking down.
    up = forward.y < 0 ? glm::vec3(0, 0, -1) : glm::vec3(0, 0, 1);
  }
  up = glm::normalize(up);
  float a = glm::radians(twistDegrees);
  glm::vec3 towardsViewer = -forward;
  // Rodrigues' rotation of `up` (perpendicular to the axis) by +a about the axis towards the
  // viewer.
  return glm::normalize(up * std::cos(a) + glm::cross(towardsViewer, up) * std::sin(a));
}

glm::vec3 lineOfSight(const ViewSettings& view) {
  glm::vec3 d = view.viewReference - view.viewpoint;
  float length = glm::length(d);
  return length > 0 ? d / length : glm::vec3(0, 0, -1);
}

void setFrame(Camera& camera, const glm::vec3& forward, float twistDegrees) {
  camera.forward = forward;
  camera.up = screenUp(forward, twistDegrees);
  camera.right = glm::normalize(glm::cross(forward, camera.up));
}

// cpfg: `scale factor: 0` means 1.
float scaleFactorOf(const ViewSettings& view) {
  float s = std::abs(view.scaleFactor);
  return s > 0 ? s : 1.0f;
}

// front/back distance as an ordered interval (a few corpus views give them the wrong way round).
std::pair<float, float> clippingInterval(const ViewSettings& view) {
  return std::minmax(view.frontDistance, view.backDistance);
}

void fitParallel(Camera& camera, const ViewSettings& view, const Bounds& plant) {
  // cpfg-manual §8.1.2: `box:` replaces the plant's bounds, and only in parallel projection.
  Bounds fit = view.box && !view.box->empty() ? *view.box : plant;
  glm::vec3 center = fit.empty() ? view.viewReference : fit.center();
  setFrame(camera, lineOfSight(view), view.twistDegrees);

  float halfWidth = 0, halfHeight = 0;
  if (!fit.empty()) {
    for (const glm::vec3& c : corners(fit)) {
      halfWidth = std::max(halfWidth, std::abs(glm::dot(c - center, camera.right)));
      halfHeight = std::max(halfHeight, std::abs(glm::dot(c - center, camera.up)));
    }
  }
  if (halfWidth <= 0 && halfHeight <= 0) halfWidth = halfHeight = 1;  // a point or nothing
  float aspect = static_cast<float>(camera.viewport.x) / static_cast<float>(camera.viewport.y);
  if (halfWidth > halfHeight * aspect) {
    halfHeight = halfWidth / aspect;
  } else {
    halfWidth = halfHeight * aspect;
  }
  float scale = scaleFactorOf(view);
  camera.halfWidth = halfWidth / scale;
  camera.halfHeight = halfHeight / scale;

  // The viewpoint keeps its distance from the reference point, now in front of the centre.
  float distance = glm::distance(view.viewpoint, view.viewReference);
  camera.target = center;
  camera.eye = center - camera.forward * distance;
  Bounds everything = plant;
  everything.add(fit);
  float radius = boundingRadius(everything, center);
  float margin = radius * 1e-3f + 1e-6f;
  auto [front, back] = clippingInterval(view);
  camera.nearPlane = std::max(front, distance - radius - margin);
  camera.farPlane = std::min(back, distance + radius + margin);
  if (camera.farPlane <= camera.nearPlane) camera.farPlane = camera.nearPlane + margin;

  camera.view = glm::lookAt(camera.eye, camera.target, camera.up);
  camera.projectionMatrix = glm::ortho(-camera.halfWidth, camera.halfWidth, -camera.halfHeight,
                                       camera.halfHeight, camera.nearPlane, camera.farPlane);
}

void placePerspective(Camera& camera, const ViewSettings& view, const Bounds& plant) {
  // cpfg moves the eye along the line of sight by the scale factor (manual §8.1.2; its rayshade
  // output confirms eye = reference + (viewpoint − reference) / scale).
  glm::vec3 forward = lineOfSight(view);
  float distance = glm::distance(view.viewpoint, view.viewReference);
  if (distance <= 0) distance = 1;
  camera.target = view.viewReference;
  camera.eye = view.viewReference - forward * (distance / scaleFactorOf(view));
  setFrame(camera, forward, view.twistDegrees);
  camera.fieldOfViewY = std::clamp(view.viewingAngle, 0.01f, 179.0f);

  glm::vec3 center = plant.empty() ? camera.target : plant.center();
  float radius = boundingRadius(plant, center);
  float along = glm::dot(center - camera.eye, camera.forward);
  float margin = radius * 1e-3f + 1e-6f;
  auto [front, back] = clippingInterval(view);
  camera.farPlane = std::min(back, along + radius + margin);
  // cpfg requires front ≥ 0; a zero or negative front (or an eye inside the plant) gets a near
  // plane close to the eye.
  float closest = std::max(camera.farPlane * 1e-4f, 1e-6f);
  camera.nearPlane = std::max({front, along - radius - margin, closest});
  if (camera.farPlane <= camera.nearPlane) camera.farPlane = camera.nearPlane * 2;

  float aspect = static_cast<float>(camera.viewport.x) / static_cast<float>(camera.viewport.y);
  camera.view = glm::lookAt(camera.eye, camera.target, camera.up);
  camera.projectionMatrix = glm::perspective(glm::radians(camera.fieldOfViewY), aspect,
                                             camera.nearPlane, camera.farPlane);
}

}  // namespace

glm::vec3 Camera::toPixels(const glm::vec3& world) const {
  glm::vec4 clip = viewProjection() * glm::vec4(world, 1.0f);
  glm::vec3 ndc = glm::vec3(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * static_cast<float>(viewport.x),
          (0.5f - ndc.y * 0.5f) * static_cast<float>(viewport.y), ndc.z * 0.5f + 0.5f};
}

float Camera::pixelSize() const {
  const float rows = static_cast<float>(std::max(1, viewport.y));
  if (projection == Projection::Parallel) return 2 * halfHeight / rows;
  return 2 * glm::length(target - eye) * std::tan(glm::radians(fieldOfViewY) / 2) / rows;
}

float Camera::pixelSizeAt(const glm::vec3& world) const {
  if (projection == Projection::Parallel) return pixelSize();
  const float target = glm::length(this->target - eye);
  const float depth = glm::dot(world - eye, forward);
  if (!(depth > 0) || !(target > 0)) return 0;
  return pixelSize() * depth / target;
}

Camera fitCamera(const ViewSettings& view, const Bounds& plant, glm::ivec2 viewport) {
  Camera camera;
  camera.projection = view.projection;
  camera.viewport = glm::max(viewport, glm::ivec2(1));
  if (view.projection == Projection::Perspective) {
    placePerspective(camera, view, plant);
  } else {
    fitParallel(camera, view, plant);
  }
  return camera;
}

}  // namespace hirsute
