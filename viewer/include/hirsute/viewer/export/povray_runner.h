// Runs the installed POV-Ray on an exported scene, without a display, and reports what it said:
// `hirsute export --render`, the export tests and the export benchmark use it.
#pragma once

#include <filesystem>
#include <string>

namespace hirsute {

struct PovrayRun {
  int exitStatus = -1;  // povray's exit code; -1 when it could not be started
  // The warnings and errors POV-Ray printed while parsing and rendering, as it printed them
  // (its banner, options and statistics left out); empty for a clean run.
  std::string messages;
  // From its statistics, wall seconds; -1 when it printed none: "Parse Time", "Bounding Time"
  // (the bounding hierarchy built after parsing) and "Trace Time" (the render itself).
  double parseSeconds = -1;
  double boundingSeconds = -1;
  double traceSeconds = -1;

  bool clean() const { return exitStatus == 0 && messages.empty(); }
};

// Whether an executable `povray` is on the PATH.
bool povrayAvailable();

// Renders `scene` to the PNG `image` at width × height, anti-aliased when asked. POV-Ray runs in
// the scene's folder, so that the texture images written beside it are found.
PovrayRun runPovray(const std::filesystem::path& scene, const std::filesystem::path& image,
                    int width, int height, bool antialias);

}  // namespace hirsute
