// The window's multisampled framebuffer: the scene is drawn into it and resolved into the
// window, so that antialiasing is the same as the headless path's (`--samples`) whatever visuals
// the X server offers (Xvfb has no multisampled ones).
#pragma once

#include "hirsute/viewer/gl/gl_functions.h"

namespace hirsute {

class MultisampleTarget {
 public:
  explicit MultisampleTarget(const GlFunctions& gl) : gl_(gl) {}
  ~MultisampleTarget() { release(); }
  MultisampleTarget(const MultisampleTarget&) = delete;
  MultisampleTarget& operator=(const MultisampleTarget&) = delete;

  // Makes it the target of drawing, `width` × `height` pixels with `samples` samples a pixel
  // (reduced to what GL offers); false when GL cannot make it (draw into the window then).
  bool bind(int width, int height, int samples);
  // Resolves the samples into the window's back buffer, and leaves that bound.
  void resolve();

 private:
  void release();

  const GlFunctions& gl_;
  GLuint framebuffer_ = 0, color_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0, samples_ = 0;
  bool complete_ = false;
};

}  // namespace hirsute
