// The images of textured meshes, written beside an exported scene as PNG files that the scene
// names: POV-Ray's image_map and OBJ's map_Kd read images from files, not from the scene text.
#pragma once

#include <filesystem>
#include <string>

#include "hirsute/interpreter/scene.h"
#include "hirsute/core/output_target.h"

namespace hirsute {

// The file name (no folder) of texture `index` (into Scene::textures) exported with `target`:
// "plant.pov" → "plant_texture1.png" for index 0.
std::string textureFileName(const std::filesystem::path& target, int index);

// Writes `texture`'s pixels (RGBA, row 0 at the top) as a PNG named `name` in `folder`, created
// there without following a link (output_folder.h), atomically (with the outputs of `group` when
// given). Throws std::runtime_error when it cannot, std::invalid_argument when the texture has
// no pixels.
void writeTexturePng(const Texture& texture, const OutputFolder& folder, const std::string& name,
                     OutputGroup* group = nullptr);

}  // namespace hirsute
