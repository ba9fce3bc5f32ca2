// The feathers' view-file settings (organ_settings.h; DESIGN.md, "Feathers"; docs/feathers.md):
// what `feather:` and `feather follicles:` set (feather_view_lines.cpp).
#pragma once

#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/organ_settings.h"

namespace hirsute {

// A `feather:` line: a feather type file (.fea), type k of @Fe(k) for the k-th line.
struct FeatherTypeDeclaration {
  std::string file;      // resolved against the view file's folder
  SourceLocation where;  // the file name on its view-file line
};

// The most `feather:` lines a view file may have.
inline constexpr int kMaxFeatherTypes = 1024;

// How coat follicles are laid out (`feather follicles:`, DESIGN.md "Feathers").
enum class FollicleLayout { Diffusion, Hexagonal };

struct FeatherSettings : OrganSettingsOf<FeatherSettings> {
  std::vector<FeatherTypeDeclaration> types;  // in order
  FollicleLayout follicleLayout = FollicleLayout::Diffusion;
};

}  // namespace hirsute
