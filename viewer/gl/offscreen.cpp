#include "hirsute/viewer/gl/offscreen.h"

#include <GL/osmesa.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/gl/gl_renderer.h"

// Mesa's OSMesa (22.3) never frees the buffers OSMesaMakeCurrent makes for a context, so in the
// sanitizer build LeakSanitizer is told to leave what libOSMesa allocates alone.
#if defined(__SANITIZE_ADDRESS__)
#define HIRSUTE_LEAK_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HIRSUTE_LEAK_SANITIZER 1
#endif
#endif
#ifdef HIRSUTE_LEAK_SANITIZER
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\n";
}
#endif

namespace hirsute {

struct OsMesaContext::Handle {
  OSMesaContext context = nullptr;
  // OSMesa draws into memory of ours; everything is drawn into framebuffer objects, so its own
  // buffer needs no more than a pixel.
  unsigned char pixel[4] = {};
};

OsMesaContext::OsMesaContext() : handle_(std::make_unique<Handle>()) {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  handle_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!handle_->context) {
    throw std::runtime_error("OSMesa cannot create a GL 3.3 core-profile context");
  }
  if (!OSMesaMakeCurrent(handle_->context, handle_->pixel, GL_UNSIGNED_BYTE, 1, 1)) {
    OSMesaDestroyContext(handle_->context);
    throw std::runtime_error("OSMesa cannot make its context current");
  }
  try {
    gl_ = std::make_unique<GlFunctions>(
        [](const char* name) { return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name)); });
  } catch (...) {
    OSMesaDestroyContext(handle_->context);
    throw;
  }
}

OsMesaContext::~OsMesaContext() {
  OSMesaDestroyContext(handle_->context);
}

std::string OsMesaContext::description() const {
  auto text = [&](GLenum name) {
    const GLubyte* s = gl_->GetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
  };
  return text(GL_VERSION) + " / " + text(GL_RENDERER);
}

OffscreenFramebuffer::OffscreenFramebuffer(const GlFunctions& gl, int width, int height,
                                           int samples)
    : gl_(gl), width_(width), height_(height) {
  GLint maxSize = 0, maxSamples = 0;
  gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
  gl_.GetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  if (width < 1 || height < 1 || width > maxSize || height > maxSize) {
    throw std::runtime_error("the image size " + std::to_string(width) + "x" +
                             std::to_string(height) + " is outside what GL offers (1 to " +
                             std::to_string(maxSize) + " pixels a side)");
  }
  samples_ = std::clamp(samples, 1, std::max(1, static_cast<int>(maxSamples)));

  auto attach = [&](unsigned& framebuffer, unsigned& color, unsigned* depth, int count) {
    gl_.GenFramebuffers(1, &framebuffer);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl_.GenRenderbuffers(1, &color);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, color);
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, count, GL_RGBA8, width, height);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    if (depth) {
      gl_.GenRenderbuffers(1, depth);
      gl_.BindRenderbuffer(GL_RENDERBUFFER, *depth);
      gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, count, GL_DEPTH_COMPONENT24, width,
                                         height);
      gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, *depth);
    }
    if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error("GL cannot make an offscreen framebuffer");
    }
  };
  try {
    // With one sample the drawing framebuffer is read directly; with more it is resolved into a
    // second, single-sample one first.
    attach(drawFramebuffer_, colorBuffer_, &depthBuffer_, samples_ > 1 ? samples_ : 0);
    if (samples_ > 1) attach(resolveFramebuffer_, resolveColorBuffer_, nullptr, 0);
  } catch (...) {
    release();
    throw;
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, drawFramebuffer_);
}

OffscreenFramebuffer::~OffscreenFramebuffer() {
  release();
}

void OffscreenFramebuffer::release() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  for (unsigned* f : {&drawFramebuffer_, &resolveFramebuffer_}) {
    if (*f) gl_.DeleteFramebuffers(1, f);
    *f = 0;
  }
  for (unsigned* r : {&colorBuffer_, &depthBuffer_, &resolveColorBuffer_}) {
    if (*r) gl_.DeleteRenderbuffers(1, r);
    *r = 0;
  }
}

void OffscreenFramebuffer::bind() const {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, drawFramebuffer_);
  gl_.Viewport(0, 0, width_, height_);
}

RgbaImage OffscreenFramebuffer::read() const {
  unsigned source = drawFramebuffer_;
  if (samples_ > 1) {
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, drawFramebuffer_);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFramebuffer_);
    gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                        GL_NEAREST);
    source = resolveFramebuffer_;
  }
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, source);
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  RgbaImage upsideDown(width_, height_);
  gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, upsideDown.rgba.data());
  gl_.BindFramebuffer(GL_FRAMEBUFFER, drawFramebuffer_);
  if (GLenum error = gl_.GetError(); error != GL_NO_ERROR) {
    throw std::runtime_error("GL cannot read the offscreen image (error " + std::to_string(error) +
                             ")");
  }
  // GL's rows run bottom to top.
  RgbaImage image(width_, height_);
  std::size_t row = static_cast<std::size_t>(width_) * 4;
  for (int y = 0; y < height_; ++y) {
    std::copy_n(&upsideDown.rgba[static_cast<std::size_t>(height_ - 1 - y) * row], row,
                &image.rgba[static_cast<std::size_t>(y) * row]);
  }
  return image;
}

RgbaImage renderOffscreen(const Scene& scene, const ViewSettings& view, bool materialMode,
                          const OffscreenOptions& options) {
  OsMesaContext context;
  OffscreenFramebuffer framebuffer(context.gl(), options.width, options.height, options.samples);
  GlRenderer renderer(context.gl());
  renderer.upload(scene, view, materialMode);
  framebuffer.bind();
  renderer.draw(fitCamera(view, scene.bounds(), {options.width, options.height}));
  return framebuffer.read();
}

}  // namespace hirsute
