// The feathers' view-file settings (organ_settings.h; docs/design.md and docs/feathers.md):
// what `feather:`, `feather follicles:` and the `dynamics …:` lines of the coat's dynamics
// (docs/dynamics.md) set (feather_view_lines.cpp).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

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

// How coat follicles are laid out (`feather follicles:`, docs/design.md, "Feathers").
enum class FollicleLayout { Diffusion, Hexagonal };

// The `dynamics …:` lines of a view file (docs/dynamics.md): the forces on simulated feathers,
// their springs, and how near they may come. Command-line options override them.
struct FeatherDynamicsSettings {
  glm::vec3 gravity{0, -9.81f, 0};  // `dynamics gravity: x y z`: cpfg's world has +y up
  float drag = 0.05f;               // `dynamics drag: c`, per unit length per unit speed
  glm::vec3 wind{0.0f};             // `dynamics wind: x y z`, the steady wind
  float gustStrength = 0;           // `dynamics gusts: strength scale period [seed]`
  float gustScale = 1;
  float gustPeriod = 1;
  unsigned gustSeed = 1;
  float stiffness = 200;            // `dynamics springs: k b`: the gold springs
  float damping = 2;
  float thickness = 0.01f;          // `dynamics thickness: t separation`
  float separation = 0.002f;
  int segments = 8;                 // `dynamics segments: n`: of each feather's stem
  int substeps = 4;                 // `dynamics substeps: n`: steps per frame
  bool vanes = false;               // `dynamics vanes: on|off`: the vanes collide
};

struct FeatherSettings : OrganSettingsOf<FeatherSettings> {
  std::vector<FeatherTypeDeclaration> types;  // in order
  FollicleLayout follicleLayout = FollicleLayout::Diffusion;
  // `feather shingling: on|off`: a still coat is laid on the layer beneath (docs/feathers.md).
  bool shingling = true;
  // Feather-coat dynamics (docs/design.md; docs/dynamics.md, "hirsute simulate"): the `dynamics …:`
  // lines. Lengths are the model's units, times seconds.
  FeatherDynamicsSettings dynamics;
};

}  // namespace hirsute
