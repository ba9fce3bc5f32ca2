// `hirsute feather-scan SCAN -o TYPE.fea`: a feather type read from a flatbed scan of a feather
// (hairs/feathers/feather_scan.h; docs/feathers.md, "Feather types from scans").
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "command.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/core/input_file.h"
#include "hirsute/core/output_target.h"
#include "hirsute/hairs/feathers/feather_file.h"
#include "hirsute/hairs/feathers/feather_scan.h"
#include "hirsute/interpreter/texture_image.h"
#include "hirsute/viewer/view/png_image.h"

namespace hirsute::cli {
namespace {

namespace fs = std::filesystem;

// The largest scan file read: 16 Mpixel of 16-bit RGBA, the widest pixels an image format here
// stores, with room for its header.
constexpr std::size_t kMaxScanFileBytes = std::size_t{160} << 20;

struct FeatherScanCommandOptions {
  std::string scan;
  std::string output;
  std::string texture;
  double dpi = 300;
  std::optional<double> length;
  std::string base = "auto";
  bool back = false;
  int keyBarbs = 3;
  int textureSize = 512;
};

// The scan's bytes are read whole (a regular file only: a FIFO or a device is refused at once)
// and its header's size is checked before its pixels are decoded: a picture over the scanner's
// limit costs no more than reading its file.
Texture readScan(const std::string& scan) {
  const SourceLocation where{std::make_shared<const std::string>(scan), 0, 0};
  std::string text;
  std::string failure;
  if (!readInputFile(scan, text, failure, kMaxScanFileBytes))
    throw DiagnosticError(where, "cannot read the scan: " + failure);
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  text = std::string();
  if (const std::optional<ImageExtent> extent = imageExtentOf(bytes)) {
    if (static_cast<long long>(extent->width) * extent->height > kMaxScanPixels) {
      throw DiagnosticError(
          where, fmt::format("the scan has {} × {} pixels, more than {} Mpixel (the limit); scale "
                             "it down",
                             extent->width, extent->height, kMaxScanPixels >> 20));
    }
  }
  return decodeTexture(bytes, scan);
}

int runFeatherScan(const FeatherScanCommandOptions& o) {
  FeatherScanOptions options;
  options.unitsPerPixel = 2.54 / o.dpi;  // centimetres
  options.length = o.length;
  options.back = o.back;
  options.keyBarbs = o.keyBarbs;
  options.base = o.base == "top"      ? ScanBase::Top
                 : o.base == "bottom" ? ScanBase::Bottom
                 : o.base == "left"   ? ScanBase::Left
                 : o.base == "right"  ? ScanBase::Right
                                      : ScanBase::Auto;
  // The texture is named in the .fea relative to it, and a .fea reads nothing outside its folder.
  std::string textureName;
  if (!o.texture.empty()) {
    const fs::path folder = fs::absolute(o.output).lexically_normal().parent_path();
    const fs::path relative = fs::absolute(o.texture).lexically_normal().lexically_relative(folder);
    if (relative.empty() || *relative.begin() == "..") {
      std::cerr << "hirsute: error: --texture " << o.texture
                << " must lie in the folder of the .fea or below it (the .fea names it from "
                   "there)\n";
      return kExitBadInput;
    }
    textureName = relative.generic_string();
  }
  Texture image;
  FeatherScan found;
  try {
    image = readScan(o.scan);
    found = scanFeather(image, options);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << printableText(o.scan + ": error: " + e.what()) << '\n';
    return kExitBadInput;
  }
  const std::string text = featherFileText(found, fs::path(o.scan).filename().string(), textureName);
  // What it wrote must read back as a feather type.
  try {
    Diagnostics quiet;
    parseFeatherType(featherFileText(found, o.scan), o.output, quiet);
  } catch (const DiagnosticError& e) {
    std::cerr << "hirsute: error: the feather type read from the scan does not make a valid "
                 "file: "
              << e.diagnostic().text() << '\n';
    return kExitBadInput;
  }
  // The .fea and its texture are renamed into place together: a run that fails leaves both
  // files as they were.
  try {
    OutputGroup outputs;
    if (!textureName.empty()) {
      const Texture vane = vaneTextureOf(image, found, o.textureSize);
      RgbaImage png(vane.width, vane.height);
      png.rgba = vane.rgba;
      writePng(o.texture, png, &outputs);
    }
    OutputTarget file(o.output, &outputs);
    std::fputs(text.c_str(), file.stream());
    file.commit();
    outputs.commit();
  } catch (const std::runtime_error& e) {
    std::cerr << printableText(std::string("hirsute: error: ") + e.what()) << '\n';
    return kExitIoError;
  }
  for (const std::string& note : found.notes) std::cerr << o.scan << ": warning: " << note << '\n';
  const FeatherType& t = found.type;
  std::cout << fmt::format(
      "{}: a feather of {:.3g} + {:.3g} units (calamus + rachis), rachis width {:.3g}, "
      "{} + {} silhouette points, barb angles {:.0f}-{:.0f} (left) {:.0f}-{:.0f} (right), "
      "{} key barbs, tilted {:.1f} degrees; written to {}\n",
      o.scan, t.calamusLength, t.rachisLength, t.rachisWidth, t.left.silhouette.size(),
      t.right.silhouette.size(), t.left.baseAngle, t.left.tipAngle, t.right.baseAngle,
      t.right.tipAngle, t.keyBarbs.size(), found.tiltDegrees, o.output);
  return kExitOk;
}

}  // namespace

void registerFeatherScanCommand(CLI::App& app, Action& action) {
  auto o = std::make_shared<FeatherScanCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "feather-scan",
      "Read a feather type (.fea) from a flatbed scan of a feather on a plain background");
  command->add_option("scan", o->scan, "The scan: PNG, JPEG, TGA, BMP, … (a feather, front up)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--output", o->output, "The feather type file to write")->required();
  command->add_option("--dpi", o->dpi, "The scan's resolution: the type is in centimetres (default 300)")
      ->check(finiteRange(1, 100000));
  command
      ->add_option("--length", o->length,
                   "The feather's length (calamus base to rachis tip) in model units, instead of "
                   "--dpi")
      ->check(finiteRange(1e-6, 1e6));
  command->add_option("--base", o->base, "Where the calamus is: auto (the narrower end), top, bottom, left, right")
      ->check(CLI::IsMember({"auto", "top", "bottom", "left", "right"}));
  command->add_flag("--back", o->back, "The scan shows the feather's back: its vanes swap sides");
  command->add_option("--key-barbs", o->keyBarbs, "Key barbs proposed a vane (default 3)")
      ->check(CLI::Range(1, 8));
  command
      ->add_option("--texture", o->texture,
                   "Also write the scan's vane as a texture (PNG) for the type's vane mapping")
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            return fs::path(name).extension() == ".png" ? std::string() : "'" + name + "' is not a .png file";
          },
          "FILE.png"));
  command->add_option("--texture-size", o->textureSize, "The texture's size in texels (default 512)")
      ->check(CLI::Range(16, 4096));
  command->callback([o, &action] { action = [o] { return runFeatherScan(*o); }; });
}

}  // namespace hirsute::cli
