// libFuzzer target: arbitrary bytes as an animation file (`.a`, cpfg-manual §8.2) through
// parseAnimationText, the reader readAnimationFile goes through, and the frames it gives for
// derivations of a few lengths (up to 10 000: a file that means every step makes a frame of each,
// and longer derivations only make the vector longer, not the arithmetic different).
//
// A DiagnosticError is the expected answer to broken input; anything else (another exception,
// a crash, a sanitizer report, a hang, memory beyond libFuzzer's limit) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hirsute/core/diagnostic.h"
#include "hirsute/viewer/interaction/animation_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
  try {
    const hirsute::AnimationSettings settings =
        hirsute::parseAnimationText(text, "fuzz.a", diagnostics);
    for (const int length : {0, 1, 100, 10'000}) hirsute::animationFrames(settings, length);
  } catch (const hirsute::DiagnosticError&) {
  }
  return 0;
}
