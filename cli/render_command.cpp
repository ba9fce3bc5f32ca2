// `hirsute render`: the model drawn headless (OSMesa) into a PNG, framed as cpfg frames it.
#include <cctype>
#include <cstdint>
#include <iostream>
#include <memory>
#include <string>

#include "command.h"
#include "drawing_commands.h"
#include "drawing_loader.h"
#include "hirsute/viewer/view/png_image.h"

namespace hirsute::cli {

void registerRenderCommand(CLI::App& app, Action& action) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* render =
      app.add_subcommand("render",
                         "Render the model headless to a picture (PNG, JPEG; OpenEXR with "
                         "--trace), with the view file's camera and lights");
  addModelOptions(*render, options->model);
  render
      ->add_option("-o,--output", options->output,
                   "The picture to write, in the format its extension names: .png, .jpg or "
                   ".jpeg (JPEG, quality 95); with --trace also .exr (OpenEXR, linear half "
                   "floats)")
      ->required();
  render
      ->add_option("--size", options->size, "Image size in pixels, WIDTHxHEIGHT (default 800x600)")
      ->check(imageSizeCheck());
  render
      ->add_option("--samples", options->samples,
                   "Multisample antialiasing: samples a pixel (default 4; 1 turns it off)")
      ->check(CLI::Range(1, 64));
  render->add_flag("--trace", options->trace,
                   "Render by the path tracer (Monte-Carlo, hairs, translucency, sky light) "
                   "instead of GL");
  render
      ->add_option("--spp", options->traceSamples,
                   "With --trace: samples a pixel, at most (default 64)")
      ->check(integerRange(1, 1 << 20));
  render
      ->add_option("--noise", options->traceNoise,
                   "With --trace: adaptive sampling; a tile of 8x8 pixels stops taking samples "
                   "once its noisiest pixel's estimated error is under LEVELS display levels "
                   "(default 4; 0-255, 0: every pixel takes --spp)")
      ->type_name("LEVELS")
      ->check(finiteRange(0, 255));
  render
      ->add_option("--spp-image", options->sampleCountImage,
                   "With --trace: also write each pixel's sample count to this PNG "
                   "(grey, white for --spp)")
      ->type_name("FILE");
  render
      ->add_option("--time", options->traceSeconds,
                   "With --trace: stop the passes before this many seconds (default: none)")
      ->check(finiteRange(0, 1e7));
  render->add_flag("--denoise", options->traceDenoise,
                   "With --trace: filter the finished picture by each pixel's noise and what its "
                   "camera rays met first (needs --spp 2 or more)");
  render
      ->add_option("--seed", options->traceSeed,
                   "With --trace: the seed of the samples (default 1; one seed, one picture)")
      ->check(integerRange(0, UINT64_MAX));
  render
      ->add_option("--bits", options->bits,
                   "With --trace: 8 (sRGB, default) or 16 bits a channel (linear light) in the PNG")
      ->check(CLI::IsMember({8, 16}));
  render
      ->add_option("--exposure", options->exposure,
                   "With --trace: brighten (or darken, below 0) the picture by EV stops, a factor "
                   "of 2^EV on its linear light (default 0; -20 to 20; not in .exr files)")
      ->type_name("EV")
      ->check(finiteRange(-20, 20));
  render
      ->add_option("--tone", options->tone,
                   "With --trace: the tone curve of the 8-bit picture: none (clip at white, the "
                   "default) or filmic (highlights roll off towards white)")
      ->type_name("CURVE")
      ->check(CLI::IsMember({"none", "filmic"}));
  render
      ->add_option("--filter", options->filter,
                   "With --trace: the pixel filter: box (each pixel its own samples, the "
                   "default), gaussian (radius 1.5 pixels) or mitchell (Mitchell-Netravali, "
                   "radius 2: sharper)")
      ->type_name("FILTER")
      ->check(CLI::IsMember({"box", "gaussian", "mitchell"}));
  render
      ->add_option("--aperture", options->aperture,
                   "With --trace: depth of field; the lens's diameter in the model's units "
                   "(default 0: a pinhole, everything sharp)")
      ->type_name("D")
      ->check(finiteRange(0, 1e9));
  render
      ->add_option("--focus", options->focus,
                   "With --trace and --aperture: the distance from the eye, along the line of "
                   "sight, of the plane in focus (default: the point the view looks at)")
      ->type_name("DIST")
      ->check(finiteRange(1e-9, 1e12));
  render->callback([options, &action, render] {
    options->exposureGiven = render->count("--exposure") > 0;
    options->toneGiven = render->count("--tone") > 0;
    options->filterGiven = render->count("--filter") > 0;
    options->apertureGiven = render->count("--aperture") > 0;
    options->focusGiven = render->count("--focus") > 0;
    const std::optional<ImageFormat> format = imageFormatOf(options->output);
    if (!format) {
      throw CLI::ValidationError("--output",
                                 "'" + options->output +
                                     "': the picture's format is chosen by its extension: " +
                                     kImageExtensions + " (and .exr with --trace)");
    }
    const bool exr = format == ImageFormat::Exr;
    if (!options->trace && (exr || options->bits != 8)) {
      throw CLI::ValidationError(exr ? "--output" : "--bits",
                                 "an OpenEXR file and 16-bit PNGs are made by --trace only");
    }
    if (format == ImageFormat::Jpeg && options->bits != 8) {
      throw CLI::ValidationError("--bits", "a JPEG holds 8 bits a channel; --bits 16 is for PNGs");
    }
    if (!options->trace && !options->sampleCountImage.empty()) {
      throw CLI::ValidationError("--spp-image", "sample counts are made by --trace only");
    }
    if (!options->sampleCountImage.empty()) {
      const std::optional<ImageFormat> counts = imageFormatOf(options->sampleCountImage);
      if (!counts || counts == ImageFormat::Exr) {
        throw CLI::ValidationError("--spp-image", "'" + options->sampleCountImage +
                                                      "': the picture's format is chosen by its "
                                                      "extension: " +
                                                      kImageExtensions);
      }
    }
    if (!options->trace && (options->aperture != 0 || options->focus != 0)) {
      throw CLI::ValidationError(options->aperture != 0 ? "--aperture" : "--focus",
                                 "depth of field is for traced pictures (--trace)");
    }
    if (!options->trace && options->filter != "box") {
      throw CLI::ValidationError("--filter", "pixel filters are for traced pictures (--trace)");
    }
    if (!options->trace && (options->exposure != 0 || options->tone != "none")) {
      throw CLI::ValidationError(options->exposure != 0 ? "--exposure" : "--tone",
                                 "exposure and tone curves are for traced pictures (--trace)");
    }
    if (options->trace && (exr || options->bits == 16) && options->tone != "none") {
      throw CLI::ValidationError("--tone", exr ? "an OpenEXR file holds linear radiance; a tone "
                                                 "curve is for 8-bit pictures"
                                               : "a 16-bit PNG holds linear light; a tone curve "
                                                 "is for 8-bit pictures");
    }
    if (exr && options->exposure != 0) {
      throw CLI::ValidationError("--exposure",
                                 "an OpenEXR file holds the radiance as traced; expose it when "
                                 "grading, or write a PNG");
    }
    if (!options->trace && options->traceDenoise) {
      throw CLI::ValidationError("--denoise", "only a traced picture (--trace) is denoised");
    }
    if (options->traceDenoise && options->traceSamples < 2) {
      throw CLI::ValidationError("--denoise",
                                 "the denoiser needs each pixel's noise: --spp 2 or more");
    }
    if (options->traceDenoise) {
      // The filter keeps some 350 bytes a pixel besides the tracer's 52: 6 GB at this limit.
      constexpr long long kMostDenoisedPixels = 4096LL * 4096LL;
      const auto x = options->size.find('x');
      const long long pixels =
          std::stoll(options->size.substr(0, x)) * std::stoll(options->size.substr(x + 1));
      if (pixels > kMostDenoisedPixels) {
        throw CLI::ValidationError("--denoise",
                                   "a denoised picture has at most 4096x4096 pixels (" +
                                       std::to_string(kMostDenoisedPixels) + "); --size asks for " +
                                       std::to_string(pixels));
      }
    }
    if (exr && options->bits != 8) {
      throw CLI::ValidationError("--bits", "an OpenEXR file holds half floats; --bits is for PNGs");
    }
    if (options->trace) {
      action = [options] { return runInTraceModule("hirsuteRunTrace", options.get()); };
      return;
    }
    action = [options] { return runInDrawingModule("hirsuteRunRender", options.get()); };
  });
}

}  // namespace hirsute::cli
