// `hirsute render --trace`: the model's still by the path tracer (docs/trace.md), framed as the
// GL render frames it, so that a preview and a still of one view line up.
#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <iostream>
#include <new>
#include <optional>
#include <string>

#include "command.h"
#include "drawing_commands.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/core/output_target.h"
#include "hirsute/viewer/trace/exr_image.h"
#include "hirsute/viewer/trace/path_tracer.h"
#include "hirsute/viewer/trace/scene_geometry.h"
#include "hirsute/viewer/trace/sky_model.h"
#include "hirsute/viewer/view/view_lighting.h"

namespace hirsute::cli {
namespace {

// What the tracer keeps a pixel while it traces (radiance, sums, squares, counts: 52 bytes) and
// what writing it takes (the 8-bit picture and its RGB copy, or the 16-bit one).
constexpr std::size_t kTracedBytesPerPixel = 64;
// What the denoiser keeps a pixel besides (denoise.h: the features and their variances).
constexpr std::size_t kDenoisedBytesPerPixel = 350;

}  // namespace

int runTrace(const RenderOptions& o) {
  using Clock = std::chrono::steady_clock;
  Progress progress = Progress::onTerminal(stderr);
  ModelOptions model = o.model;
  model.terminalProgress = &progress;
  // The picture's own buffers are reserved before the model is built, so that a picture too
  // large for the machine is named as such, not blamed on the model.
  const glm::ivec2 size = imageSize(o.size);
  const std::size_t pixels = static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y);
  const std::size_t bytesPerPixel =
      kTracedBytesPerPixel + (o.traceDenoise ? kDenoisedBytesPerPixel : 0);
  const std::size_t imageBytes = pixels * bytesPerPixel;
  {
    // Called, not a new-expression, and kept in a volatile: the allocation cannot be elided.
    void* volatile reserved = ::operator new(imageBytes, std::nothrow);
    if (reserved == nullptr) {
      std::cerr << fmt::format(
          "hirsute: error: out of memory for the traced picture's buffers: {}x{} pixels take "
          "{:.1f} GB ({} bytes a pixel), more than this machine holds; lower --size\n",
          size.x, size.y, imageBytes / 1e9, bytesPerPixel);
      return kExitBadInput;
    }
    ::operator delete(reserved);
  }
  Diagnostics diagnostics(&std::cerr);
  std::optional<BuiltScene> built = buildSceneOrSay(model, diagnostics, progress);
  if (!built) return kExitBadInput;
  const Scene& scene = built->scene;
  const ViewSettings& view = built->resources.view;
  const Bounds bounds = scene.bounds();
  const Camera camera = fitCamera(view, bounds, size);

  // Without a `trace light:` line the light comes from where the view's first light shines
  // from, as in the GL render; with none, from the eye.
  const ViewLighting lighting = viewLighting(view, built->resources.materialMode, -camera.forward);
  trace::TraceLights lights =
      trace::traceLights(view.trace, bounds, traceLightFallback(lighting, bounds, -camera.forward));
  try {
    // A large map takes seconds to decode and to make its sampling tables.
    std::optional<ProgressHeartbeat> heartbeat;
    if (!view.trace.environment.empty()) {
      progress.begin("reading the environment map", Progress::Unit::None);
      heartbeat.emplace(progress);
    }
    trace::addViewSky(view.trace, bounds, camera, lights);
  } catch (const DiagnosticError& e) {
    progress.clear();
    std::cerr << e.diagnostic().text() << '\n';
    return kExitBadInput;
  }
  // The view file's camera lines, unless the command line gives the option.
  const TraceSettings& look = view.trace;
  const float exposure = o.exposureGiven ? o.exposure : look.exposure.value_or(0.0f);
  const std::string tone = o.toneGiven ? o.tone : look.tone.value_or("none");
  const std::string filter = o.filterGiven ? o.filter : look.filter.value_or("box");
  const double aperture = o.apertureGiven ? o.aperture : look.aperture.value_or(0.0f);
  const double focus = o.focusGiven ? o.focus : look.focus.value_or(0.0f);
  if (focus != 0 && aperture == 0) {
    std::cerr << "hirsute: error: --focus: a pinhole has everything in focus: give the lens an "
                 "--aperture (or the view file a 'trace aperture:' line)\n";
    return kExitBadInput;
  }

  trace::TraceOptions options;
  options.samples = o.traceSamples;
  options.noise = o.traceNoise;
  options.seconds = o.traceSeconds;
  options.threads = o.model.threads;
  options.seed = o.traceSeed;
  options.denoise = o.traceDenoise;
  options.background = backgroundColor(scene, built->resources.materialMode);
  options.progress = &progress;
  options.aperture = static_cast<float>(aperture);
  options.focusDistance = static_cast<float>(focus);
  options.filter = trace::pixelFilterNamed(filter).value_or(trace::PixelFilterKind::Box);
  // The 16-bit PNG is exposed but not tone-mapped (linear light); OpenEXR is neither: the view
  // file's exposure and curve are for the pictures that show them.
  const bool exr = imageFormatOf(o.output).value_or(ImageFormat::Png) == ImageFormat::Exr;
  if (o.bits == 16) options.display.exposure = exposure;
  if (o.bits == 8 && !exr) {
    options.display.exposure = exposure;
    options.display.tone = trace::toneCurveNamed(tone).value_or(trace::ToneCurve::None);
  }
  trace::TraceImage image;
  try {
    const Clock::time_point started = Clock::now();
    progress.begin("building the ray tracer's scene", Progress::Unit::None);
    std::optional<ProgressHeartbeat> heartbeat(std::in_place, progress);
    trace::TraceScene traced(view.trace, o.model.threads);
    // With a colour map, the colours GL shades along the palette (view_lighting.h).
    traced.setLitPaletteOffset(
        litPaletteOffset(view, built->resources.materialMode, built->resources.colorMapFile));
    trace::addSceneGeometry(scene, camera, traced);
    if (look.ground)
      trace::addGroundPlane(traced, bounds, lights.up, trace::linearColour(*look.ground));
    traced.commit();
    heartbeat.reset();
    progress.clear();
    if (o.model.verbose) {
      std::cerr << fmt::format(
          "ray tracer's scene: {} triangles, {} curve segments, {:.1f} MB of buffers in {:.3f} "
          "s\n",
          traced.triangleCount(), traced.curveSegments(), traced.bufferBytes() / 1e6,
          std::chrono::duration<double>(Clock::now() - started).count());
    }
    try {
      image = trace::traceImage(traced, camera, lights, options);
    } catch (const std::bad_alloc&) {
      progress.clear();
      std::cerr << fmt::format(
          "hirsute: error: out of memory while tracing the {}x{} picture: its buffers ({:.1f} "
          "GB) and the ray tracer's scene ({:.1f} GB) take more than this machine holds; lower "
          "--size\n",
          size.x, size.y, imageBytes / 1e9, traced.bufferBytes() / 1e9);
      return kExitBadInput;
    }
  } catch (const GeometryLimitError& e) {
    progress.clear();
    std::cerr << model.lsystemFile << ": error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::runtime_error& e) {
    progress.clear();
    std::cerr << "hirsute: error: cannot trace: " << e.what() << '\n';
    return kExitIoError;
  }
  progress.clear();
  if (o.model.verbose) {
    std::cerr << fmt::format(
        "traced {:.1f} samples a pixel on average, at most {}, at {}x{} in {:.3f} s{}\n",
        image.meanSamples(), image.passes, image.width, image.height, image.seconds,
        o.traceDenoise ? fmt::format(" (denoised in {:.3f} s)", image.denoiseSeconds) : "");
  }
  // The picture and its sample counts are renamed into place together: a run that fails
  // leaves both files as they were.
  try {
    OutputGroup outputs;
    const ImageFormat format = imageFormatOf(o.output).value_or(ImageFormat::Png);
    if (format == ImageFormat::Exr) {
      trace::writeExr(o.output, image.width, image.height, image.radiance, &outputs);
    } else if (o.bits == 16) {
      // Linear light: the exposure chooses what is white, no curve bends it. In place: the
      // picture's buffers hold no second copy.
      const float scale = std::exp2(exposure);
      for (glm::vec3& c : image.radiance) c *= scale;
      writeLinearPng16(o.output, image.width, image.height, image.radiance, &outputs);
    } else {
      writeImage(o.output, trace::displayImage(image, options.display), format, &outputs);
    }
    if (!o.sampleCountImage.empty()) {
      writeImage(o.sampleCountImage, trace::sampleCountImage(image, o.traceSamples),
                 imageFormatOf(o.sampleCountImage).value_or(ImageFormat::Png), &outputs);
    }
    outputs.commit();
  } catch (const std::runtime_error& e) {
    std::cerr << printableText(std::string("hirsute: error: ") + e.what()) << '\n';
    return kExitIoError;
  }
  return kExitOk;
}

}  // namespace hirsute::cli
