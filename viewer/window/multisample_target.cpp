#include "hirsute/viewer/window/multisample_target.h"

#include <algorithm>

namespace hirsute {

bool MultisampleTarget::bind(int width, int height, int samples) {
  if (width != width_ || height != height_ || samples != samples_) {
    release();
    GLint maxSamples = 1;
    gl_.GetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    int count = std::clamp(samples, 1, std::max(1, static_cast<int>(maxSamples)));
    gl_.GenFramebuffers(1, &framebuffer_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    gl_.GenRenderbuffers(1, &color_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, color_);
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, count, GL_RGBA8, width, height);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
    gl_.GenRenderbuffers(1, &depth_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, depth_);
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, count, GL_DEPTH_COMPONENT24, width, height);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    width_ = width;
    height_ = height;
    samples_ = samples;
    complete_ = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, complete_ ? framebuffer_ : 0);
  return complete_;
}

void MultisampleTarget::resolve() {
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void MultisampleTarget::release() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (framebuffer_) gl_.DeleteFramebuffers(1, &framebuffer_);
  if (color_) gl_.DeleteRenderbuffers(1, &color_);
  if (depth_) gl_.DeleteRenderbuffers(1, &depth_);
  framebuffer_ = color_ = depth_ = 0;
  width_ = height_ = samples_ = 0;
  complete_ = false;
}

}  // namespace hirsute
