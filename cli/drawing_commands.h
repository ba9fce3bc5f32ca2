// The options of the commands that draw (`render`, `view`), shared by the program, which parses
// them, and the drawing module (libhirsute-drawing.so, drawing_module.cpp), which runs them: the
// program itself loads no GL library, so that every command that draws nothing starts without
// one (drawing_loader.h).
#pragma once

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "model_pipeline.h"

namespace hirsute::cli {

struct RenderOptions {
  ModelOptions model;
  std::string output;
  std::string size = "800x600";
  int samples = 4;
  // --trace: the path tracer instead of GL (trace_run.cpp, in the trace module).
  bool trace = false;
  int traceSamples = 64;
  float traceNoise = 4;          // --noise: adaptive sampling's target, display levels (0: off)
  std::string sampleCountImage;  // --spp-image: each pixel's sample count as grey
  double traceSeconds = 0;
  std::uint64_t traceSeed = 1;
  bool traceDenoise = false;    // --denoise: filter the traced picture (denoise.h)
  int bits = 8;  // --bits: 8 (sRGB) or 16 (linear light, with --trace)
  float exposure = 0;         // --exposure: stops, with --trace (tone_curve.h)
  std::string tone = "none";  // --tone: none or filmic, with --trace
  std::string filter = "box";  // --filter: box, gaussian or mitchell, with --trace
  double aperture = 0;         // --aperture: the lens's diameter, with --trace
  double focus = 0;            // --focus: the distance in focus (0: the point looked at)
  // Which of the five above the command line gave: they override the view file's lines.
  bool exposureGiven = false, toneGiven = false, filterGiven = false, apertureGiven = false,
       focusGiven = false;
};

struct ViewOptions {
  ModelOptions model;
  std::string animation;
  std::string commands;
  std::string scriptFile;
  std::string size = "800x600";
  int samples = 4;
  bool save = false;
  bool noWatch = false;
  bool noPanel = false;
  std::size_t movingHairs = 20000;
};

// `--size`'s WIDTHxHEIGHT, already checked by its validator.
inline glm::ivec2 imageSize(const std::string& size) {
  const std::size_t x = size.find('x');
  return {std::stoi(size.substr(0, x)), std::stoi(size.substr(x + 1))};
}

// In the drawing module.
int runRender(const RenderOptions& options);
// In the trace module: the path tracer needs no GL.
int runTrace(const RenderOptions& options);
int runView(const ViewOptions& options);

}  // namespace hirsute::cli

// The drawing module's entry points (C names, found with dlsym): each runs its command and
// returns its exit code; nothing is thrown across.
extern "C" int hirsuteRunRender(const hirsute::cli::RenderOptions* options);
extern "C" int hirsuteRunView(const hirsute::cli::ViewOptions* options);
