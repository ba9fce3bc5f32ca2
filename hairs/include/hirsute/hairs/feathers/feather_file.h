// Reading feather type files (`.fea`, docs/feathers.md, "The feather file") into FeatherType.
#pragma once

#include <filesystem>
#include <string_view>

#include "hirsute/core/diagnostic.h"
#include "hirsute/hairs/feathers/feather_type.h"

namespace hirsute {

// Reads a .fea file and, recursively, its afterfeather. Throws DiagnosticError at the file's
// line:col for every error (docs/feathers.md lists them); warnings go to `diagnostics`.
FeatherType loadFeatherType(const std::filesystem::path& file, Diagnostics& diagnostics);

// The same for text already read; `file` names it in diagnostics and is the folder that
// afterfeather and texture names are relative to.
FeatherType parseFeatherType(std::string_view text, const std::filesystem::path& file,
                             Diagnostics& diagnostics);

}  // namespace hirsute
