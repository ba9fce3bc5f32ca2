// Runs the installed POV-Ray on an exported scene, without a display, and reports what it said:
// `hirsute export --render`, the export tests and the export benchmark use it.
//
// A scene is untrusted code (POV-Ray's language reads and writes files), so POV-Ray runs
// confined (child_confinement.h): it reads beneath the scene's folder and POV-Ray's own folders
// and writes only a private work folder; the image comes on its standard output into a
// temporary file renamed over the image when POV-Ray succeeded. The scene reaches POV-Ray's
// option parser under a fixed name (a link in the work folder), never its own, and POV-Ray and
// all it starts end when the time limit passes.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "hirsute/core/progress.h"

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
  bool timedOut = false;  // stopped at the time limit
  int interruptedBy = 0;  // stopped because this process received SIGINT, SIGTERM or SIGHUP

  bool clean() const { return exitStatus == 0 && messages.empty(); }
};

// Whether an executable `povray` is on the PATH.
bool povrayAvailable();

// Renders `scene` to the PNG `image` at width × height, anti-aliased when asked, in at most
// `timeLimit`. POV-Ray runs in the scene's folder, so that the texture images written beside it
// are found. The image is written only when POV-Ray succeeded. With `progress`, the line shows
// the share of the pixels POV-Ray reports rendered, and the time elapsed before it reports any.
PovrayRun runPovray(const std::filesystem::path& scene, const std::filesystem::path& image,
                    int width, int height, bool antialias,
                    std::chrono::seconds timeLimit = std::chrono::seconds(3600),
                    Progress* progress = nullptr);

// POV-Ray's last report of its render in `output`, "Rendered 1024 of 307200 pixels (0%)" (it
// writes one on its standard error every few rows, each ended by a carriage return); none
// before the first whole one.
struct PixelsRendered {
  long long done = 0;
  long long total = 0;
};
std::optional<PixelsRendered> lastPixelsRendered(std::string_view output);

}  // namespace hirsute
