#include "simulate_options.h"

#include <cmath>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <sstream>

#include "command.h"
#include "hirsute/viewer/interaction/define_editor.h"

namespace hirsute::cli {

void addSimulateOptions(CLI::App& command, SimulateOptions& options) {
  addModelOptions(command, options.model);
  command
      .add_option("animation", options.animation,
                  "The .a animation file: the body moves through its frames")
      ->check(CLI::ExistingFile);
  command.add_option("-o,--output", options.output, "The folder the frames are written to")
      ->required();
  command.add_option("--animate", options.animate,
                     "NAME=FROM:TO: move the .l's #define NAME from FROM to TO over the frames "
                     "(the body moves with it)");
  command
      .add_option("--frames", options.frames, "Frames to write (default: the animation's, or 48)")
      ->check(CLI::Range(1, 1'000'000));
  command.add_option("--fps", options.fps, "Frames per second of simulated time (default 24)")
      ->check(finiteRange(0.01, 10000.0));
  command
      .add_option("--substeps", options.substeps,
                  "Time steps per frame (default: the view file's, or 4)")
      ->check(CLI::Range(1, 1000));
  command
      .add_option("--segments", options.segments,
                  "Segments of each feather's stem (default: the view file's, or 8)")
      ->check(CLI::Range(1, 64));
  // The view file's `dynamics gravity:` and `dynamics wind:` take components up to 1e6 too.
  command.add_option("--gravity", options.gravity, "Gravity X Y Z (default 0 -9.81 0)")
      ->expected(3)
      ->check(finiteRange(-1e6, 1e6));
  command.add_option("--wind", options.wind, "The steady wind X Y Z (default none)")
      ->expected(3)
      ->check(finiteRange(-1e6, 1e6));
  command.add_option("--gusts", options.gusts, "Gusts: about the largest speed they add")
      ->check(finiteRange(0.0, 1e6));
  command.add_option("--gust-scale", options.gustScale, "The size of a gust (model units)")
      ->check(finiteRange(1e-6, 1e6));
  command.add_option("--gust-period", options.gustPeriod, "Seconds over which the gusts change")
      ->check(finiteRange(1e-6, 1e6));
  command.add_option("--gust-seed", options.gustSeed, "The gusts' seed");
  command.add_option("--drag", options.drag, "Drag per unit length per unit speed")
      ->check(finiteRange(0.0, 1e6));
  command
      .add_option("--drop", options.drops,
                  "FRAME:N[:RADIUS[:WETNESS]]: N droplets on the fur at random at FRAME "
                  "(repeatable; radius 0.05, wetness 1 unless given)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return dropletFall(text, false) ? std::string() : "'" + text + "' is not FRAME:N[:RADIUS[:WETNESS]]";
          },
          "FRAME:N[:RADIUS[:WETNESS]]"));
  command
      .add_option("--rain", options.rain,
                  "RATE[:RADIUS[:WETNESS]]: droplets a second on the fur at random")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return dropletFall(text, true) ? std::string() : "'" + text + "' is not RATE[:RADIUS[:WETNESS]]";
          },
          "RATE[:RADIUS[:WETNESS]]"));
  command.add_option("--dry", options.dry, "The fur dries: wetness lost a second (0.1: in 10 s)")
      ->check(finiteRange(0.0, 1e6));
  command.add_option("--dry-from", options.dryFrom, "The frame the drying starts at (default 1)")
      ->check(CLI::Range(1, 1'000'000));
  command
      .add_option("--fur-force", options.furForce,
                  "The force X Y Z per unit mass on every fur strand (default: the view file's "
                  "`fur force:`)")
      ->expected(3)
      ->check(finiteRange(-1e6, 1e6));
  command
      .add_option("--fur-drag", options.furDrag,
                  "The force per unit mass a unit of wind speed puts on a fur strand (default 1)")
      ->check(finiteRange(0.0, 1e6));
  command.add_option("--drop-seed", options.dropSeed, "The seed of the random droplets (default 1)");
  command.add_flag("--obj", options.obj, "Write a Wavefront OBJ of every frame too");
  command.add_option("--pc2", options.pc2,
                     "Write every frame as a PC2 point cache to FILE, over a base mesh beside it "
                     "(FILE's name with .obj), for Blender's Mesh Cache modifier");
  command
      .add_option("--max-output-bytes", options.maxOutputBytes,
                  "Bytes the frames' files may take, all frames together; a run that would write "
                  "more is an error, found from the first frame before it is written (default "
                  "17179869184: 16 GiB)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 50));
  command.add_flag("--no-frames", options.noFrames,
                   "Write no scenes, only simulation.csv (to measure the simulation alone)");
  CLI::Option* vanes =
      command.add_flag("--vane-collisions", options.vaneCollisions,
                       "The feathers' vanes collide with other feathers' vanes and stems "
                       "(docs/dynamics.md, \"Vanes\"; many times the stems' cost)");
  command
      .add_flag("--no-vane-collisions", options.noVaneCollisions,
                "The vanes do not collide, whatever the view file says (their stems still do)")
      ->excludes(vanes);
  command.add_flag("--no-resting-contacts", options.noRestingContacts,
                   "No resting stage: pairs within the thickness are pushed apart by repulsion "
                   "alone, and every contact is the continuous collision detection's "
                   "(docs/dynamics.md, \"Resting contacts\"; for comparison)");
  command.add_flag("--count-vane-intersections", options.countVaneIntersections,
                   "With the vanes not colliding, count in every frame's state the vanes that "
                   "pass through each other or through stems (counted anyway when they collide)");
  addImageSizeOption(command, options.width, options.height,
                     "The frames' size in pixels, WIDTHxHEIGHT (default 800x600)");
}

std::optional<DropletFall> dropletFall(const std::string& text, bool rain) {
  std::vector<double> numbers;
  std::size_t from = 0;
  while (true) {
    const std::size_t colon = text.find(':', from);
    const std::string word = text.substr(from, colon == std::string::npos ? colon : colon - from);
    if (word.empty() || word.size() > 64) return std::nullopt;
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end != word.c_str() + word.size() || !std::isfinite(value)) return std::nullopt;
    numbers.push_back(value);
    if (colon == std::string::npos) break;
    from = colon + 1;
  }
  const std::size_t first = rain ? 0 : 1;  // a drop's frame comes before its count
  if (numbers.size() < first + 1 || numbers.size() > first + 3) return std::nullopt;
  DropletFall fall;
  if (!rain) {
    if (numbers[0] != std::floor(numbers[0]) || numbers[0] < 1 || numbers[0] > 1'000'000)
      return std::nullopt;
    fall.frame = static_cast<int>(numbers[0]);
  }
  fall.count = numbers[first];
  if (fall.count < 0 || fall.count > 10'000'000) return std::nullopt;
  if (!rain && fall.count != std::floor(fall.count)) return std::nullopt;
  if (numbers.size() > first + 1) {
    if (numbers[first + 1] < 1e-6 || numbers[first + 1] > 1) return std::nullopt;
    fall.radius = static_cast<float>(numbers[first + 1]);
  }
  if (numbers.size() > first + 2) {
    if (numbers[first + 2] < 0 || numbers[first + 2] > 1) return std::nullopt;
    fall.wetness = static_cast<float>(numbers[first + 2]);
  }
  return fall;
}

namespace {

bool isIdentifierCharacter(char c, bool first) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' ||
         (!first && c >= '0' && c <= '9');
}

}  // namespace

std::optional<AnimatedDefine> animatedDefine(const std::string& text,
                                             const std::filesystem::path& lsystem) {
  // NAME=FROM:TO, read character by character (a regular expression's recursion overflows the
  // stack on a value of some ten thousand characters): NAME an identifier, FROM up to the first
  // colon, TO the rest, on one line.
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) return std::nullopt;
  for (std::size_t i = 0; i < equals; ++i)
    if (!isIdentifierCharacter(text[i], i == 0)) return std::nullopt;
  const std::size_t colon = text.find(':', equals + 1);
  if (colon == std::string::npos || colon == equals + 1 || colon + 1 == text.size())
    return std::nullopt;
  if (text.find_first_of("\n\r", colon + 1) != std::string::npos) return std::nullopt;
  AnimatedDefine d;
  d.name = text.substr(0, equals);
  try {
    const std::string from = text.substr(equals + 1, colon - equals - 1);
    const std::string to = text.substr(colon + 1);
    std::size_t used = 0;
    d.from = std::stod(from, &used);
    if (used != from.size()) return std::nullopt;
    d.to = std::stod(to, &used);
    if (used != to.size()) return std::nullopt;
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (!std::isfinite(d.from) || !std::isfinite(d.to)) return std::nullopt;
  std::ifstream in(lsystem, std::ios::binary);
  std::ostringstream source;
  source << in.rdbuf();
  for (const DefineConstant& c : findDefineConstants(source.str()))
    if (c.name == d.name) {
      d.integer = c.integer;
      return d;
    }
  return std::nullopt;
}

}  // namespace hirsute::cli
