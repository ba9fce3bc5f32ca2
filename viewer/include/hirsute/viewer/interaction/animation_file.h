// cpfg's animation file (`.a`, cpfg-manual §8.2): which derivation steps the viewer shows as the
// frames of an animation, and how fast. Not preprocessed; one `label: value` a line; labels
// cpfg ignores (its deprecated ones, lpfg's) are ignored.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

// One entry of `frame intervals:`: a frame, or a range with its own step and a rotation or
// scaling applied after each of its frames.
struct FrameInterval {
  int first = 1, last = 1;
  int step = 1;
  std::optional<glm::vec3> rotate;  // degrees about x, y, z after each frame
  std::optional<glm::vec3> scale;   // factors after each frame
};

struct AnimationSettings {
  int firstFrame = 1;
  std::optional<int> lastFrame;  // absent (or negative in the file): the derivation length
  int step = 1;
  // Deprecated in cpfg, honoured here: the least time between two frames, in seconds (the file
  // gives tenths of a second).
  double swapIntervalSeconds = 0;
  bool clearBetweenFrames = true;
  bool scaleBetweenFrames = false;
  bool newViewBetweenFrames = false;
  bool doubleBuffer = true;
  // Takes precedence over first frame, last frame and step (cpfg-manual §8.2).
  std::vector<FrameInterval> frameIntervals;
};

// Reads an animation file. Throws DiagnosticError ("file:line:col: error: …") on a malformed
// value; warns about unknown labels.
AnimationSettings readAnimationFile(const std::filesystem::path& file, Diagnostics& diagnostics);
AnimationSettings parseAnimationText(const std::string& text, const std::string& fileName,
                                     Diagnostics& diagnostics);

// One frame of the animation: the derivation step drawn, and the turn and scaling that the frame
// intervals ask for after it.
struct AnimationFrame {
  int step = 0;
  std::optional<glm::vec3> rotateAfter, scaleAfter;
};

// The most frames an animation has, as simulate's --frames: a derivation of a billion steps
// drawn frame by frame would list 40 GB of frames before the first was drawn.
inline constexpr std::size_t kMaxAnimationFrames = 1'000'000;

// The frames in order for a model whose derivation length is `derivationLength`: first frame to
// last frame by step, or the frame intervals; frames past the derivation length are dropped
// (cpfg stops there too). The list stops one frame past kMaxAnimationFrames, so that a caller
// can tell an animation that has more.
std::vector<AnimationFrame> animationFrames(const AnimationSettings& settings,
                                            int derivationLength);

}  // namespace hirsute
