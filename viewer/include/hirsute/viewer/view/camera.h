// cpfg's camera: where the view file puts the eye, and how the plant is fitted into the window
// (docs/cli.md, "How the camera frames the plant").
#pragma once

#include <glm/glm.hpp>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"

namespace hirsute {

struct Camera {
  Projection projection = Projection::Parallel;
  glm::ivec2 viewport{1, 1};  // pixels
  // World-space frame: the eye, the point looked at, and orthonormal axes (forward is the line of
  // sight, up and right span the screen).
  glm::vec3 eye{0, 0, 1};
  glm::vec3 target{0.0f};
  glm::vec3 forward{0, 0, -1}, up{0, 1, 0}, right{1, 0, 0};
  // Parallel: the window's half size in world units. Perspective: the vertical viewing angle.
  float halfWidth = 1, halfHeight = 1;
  float fieldOfViewY = 45;                 // degrees
  float nearPlane = 0.1f, farPlane = 100;  // distances along forward from the eye
  glm::mat4 view{1.0f};                    // world → eye
  glm::mat4 projectionMatrix{1.0f};        // eye → clip

  glm::mat4 viewProjection() const { return projectionMatrix * view; }
  // Image coordinates of a world point: x to the right and y down from the top-left corner of
  // the image, in pixels (pixel (i, j) covers [i, i+1) × [j, j+1)); z is window depth 0..1.
  glm::vec3 toPixels(const glm::vec3& world) const;
  // The width of a pixel in world units at the point looked at.
  float pixelSize() const;
  // The width of a pixel in world units at `world` (its depth along the line of sight, for a
  // perspective camera; 0 at or behind the eye).
  float pixelSizeAt(const glm::vec3& world) const;
};

// The camera cpfg sets up for `view` and a plant with the given bounds, for an image of
// `viewport` pixels.
//
// Parallel projection (cpfg's auto-centring and auto-scaling): the line of sight runs from
// `viewpoint:` towards `view reference point:`, turned by `twist:`; the eye looks at the centre
// of the plant's bounding box (or of `box:` when the view file gives one), and the window is the
// smallest one of the image's aspect that holds the box's eight corners, enlarged 1/`scale
// factor` times. `front distance:` and `back distance:` clip along the line of sight measured
// from the viewpoint, which sits |viewpoint − reference point| in front of the centre.
//
// Perspective projection (no fitting, as in cpfg): the eye is the reference point plus
// (viewpoint − reference point) / scale factor, looking at the reference point with a vertical
// viewing angle of `viewing angle:`; front and back distance are clipping distances from the eye.
//
// Either way the clipping planes are drawn in to the plant's bounding sphere, so that depth
// precision is spent on the plant rather than on cpfg's ±100000 defaults.
Camera fitCamera(const ViewSettings& view, const Bounds& plant, glm::ivec2 viewport);

}  // namespace hirsute
