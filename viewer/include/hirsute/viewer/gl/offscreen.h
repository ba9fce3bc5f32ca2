// Headless rendering: an OSMesa GL context (core profile, 3.3 or later), a multisampled
// framebuffer that is resolved and read back, and the whole path from a Scene to an image.
#pragma once

#include <memory>
#include <string>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/view/png_image.h"

namespace hirsute {

// An OSMesa context, current on the calling thread from construction on. Throws
// std::runtime_error when OSMesa cannot give a core-profile context of version 3.3 or later.
class OsMesaContext {
 public:
  OsMesaContext();
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  const GlFunctions& gl() const { return *gl_; }
  // "4.5 (Core Profile) Mesa 22.3.6 / llvmpipe (…)"
  std::string description() const;

 private:
  struct Handle;
  std::unique_ptr<Handle> handle_;
  std::unique_ptr<GlFunctions> gl_;
};

// A framebuffer of `width` × `height` pixels with `samples` samples a pixel (1: none; more than
// the context offers is reduced to its maximum), colour and depth.
class OffscreenFramebuffer {
 public:
  OffscreenFramebuffer(const GlFunctions& gl, int width, int height, int samples);
  ~OffscreenFramebuffer();
  OffscreenFramebuffer(const OffscreenFramebuffer&) = delete;
  OffscreenFramebuffer& operator=(const OffscreenFramebuffer&) = delete;

  // Makes it the target of drawing.
  void bind() const;
  // Resolves the samples and reads the pixels back, top row first.
  RgbaImage read() const;
  int samples() const { return samples_; }

 private:
  void release();

  const GlFunctions& gl_;
  int width_, height_, samples_;
  unsigned drawFramebuffer_ = 0, resolveFramebuffer_ = 0;
  unsigned colorBuffer_ = 0, depthBuffer_ = 0, resolveColorBuffer_ = 0;
};

struct OffscreenOptions {
  int width = 800, height = 600;
  int samples = 4;  // multisample antialiasing; 1 turns it off
};

// The headless path: a context, the camera cpfg would set up (fitCamera), the renderer.
// `materialMode` says whether the palette came from a material file (see backgroundColor).
RgbaImage renderOffscreen(const Scene& scene, const ViewSettings& view, bool materialMode,
                          const OffscreenOptions& options);

}  // namespace hirsute
