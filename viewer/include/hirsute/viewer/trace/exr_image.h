// The path tracer's radiance as an OpenEXR file: linear light in half floats, unclamped, for
// compositing (docs/trace.md, "Output").
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <vector>

namespace hirsute {
class OutputGroup;
}

namespace hirsute::trace {

// Writes `pixels` (width × height linear RGB, row 0 at the top) as an RGB half-float OpenEXR
// image, ZIP-compressed. Values past half's range are clamped to it and a value that is not a
// number is written as 0. The file is written whole under a temporary name and renamed
// (output_target.h; with the other outputs of `group` when given); throws std::runtime_error
// "PATH: cannot write: …" and leaves no file.
void writeExr(const std::filesystem::path& path, int width, int height,
              const std::vector<glm::vec3>& pixels, OutputGroup* group = nullptr);

}  // namespace hirsute::trace
