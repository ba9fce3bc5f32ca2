// Everything a cpfg view file (.v) sets, with cpfg's defaults (cpfg-features.md (e)).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/interpreter/scene.h"

namespace hirsute {

enum class Projection { Parallel, Perspective };
enum class RenderMode { Wireframe, Filled, Flat, Interpolated, Shaded, Fast, Shadows };

struct LightSource {
  bool directional = true;              // V: direction, O: point at position
  glm::vec3 vector{1, 0, 0};            // direction (towards the light) or position
  glm::vec3 ambient{0.0f}, diffuse{1.0f}, specular{1.0f};
  // Spot (P: x y z exponent cutoff) and attenuation (T: constant linear quadratic).
  bool spot = false;
  glm::vec3 spotDirection{0, 0, -1};
  float spotExponent = 0, spotCutoff = 180;
  float constantAttenuation = 1, linearAttenuation = 0, quadraticAttenuation = 0;
};

struct Tropism {
  glm::vec3 direction{0, 1, 0};  // T:
  float angle = 0;               // A: degrees (0: gravitropism-like bending towards T)
  float intensity = 1;           // I:
  float elasticity = 0;          // E:
  float elasticityStep = 0;      // S: default increment for @Ti/@Td
  bool torque = false;           // `torque:` instead of `tropism:`
};

struct TextureDeclaration {
  std::string file;              // F:
  char mode = 'm';               // E: m modulate, d decal, b blend
  float ratio = 1;               // R:
  bool magnifyLinear = true;     // H: n|l
  std::string minify = "l";      // L: n|l|m|mnn|mln|mnl|mll
};

struct SurfaceDeclaration {
  char id = 0;
  std::string file;
  float size = 1;
  int sPrecision = 0, tPrecision = 0;  // 0: from the file
  int texture = 0;                     // 1-based, 0 none
};

struct ContourDeclaration {
  int id = 0;
  std::string file;
};

struct ViewSettings {
  // Turtle.
  float angleIncrement = 45;
  int initialColor = 128, initialBackColor = -1;  // -1: one-sided colours
  int colorIncrement = 1, backColorIncrement = 1;
  float initialLineWidth = 1;
  float lineWidthIncrement = 0;
  LineStyle lineStyle = LineStyle::Pixel;
  bool lineWidthInPixels = true;
  bool taperedLines = true;
  float initialScale = 1, scaleMultiplier = 1;
  bool interpretationPastCut = true;
  int contourSides = 8;
  bool twistOfCylinders = false;
  // Old-style tropism for `_`.
  glm::vec3 tropismDirection{0, 1, 0};
  float initialElasticity = 0, elasticityIncrement = 0;
  std::vector<Tropism> tropisms;

  // View.
  glm::vec3 viewpoint{0, 0, 1};
  glm::vec3 viewReference{0, 0, 0};
  float twistDegrees = 0;           // `twist:` is in tenths of a degree
  Projection projection = Projection::Parallel;
  float viewingAngle = 45;
  float frontDistance = -100000, backDistance = 100000;
  float scaleFactor = 1;
  std::optional<Bounds> box;        // `box:` fixes the view volume
  bool zBuffer = true;
  RenderMode renderMode = RenderMode::Filled;
  bool antialiasing = false;
  bool concavePolygons = false;

  // Lights and shading.
  std::vector<LightSource> lights;  // none given: one default light
  glm::vec3 lightDirection{1, 0, 0};  // colormap mode
  int diffuseReflection = 10;
  float surfaceAmbient = 0.15f, surfaceDiffuse = 0.75f;

  // Files the model refers to, resolved against the view file's folder.
  std::vector<ContourDeclaration> contours;
  std::vector<SurfaceDeclaration> surfaces;
  std::vector<TextureDeclaration> textures;
  std::vector<std::string> backgroundScenes;

  // Hairs (DESIGN.md): template L-systems in order, and the point-diffusion texture.
  std::vector<std::string> hairTemplates;
  int hairTextureSize = 100;
  unsigned hairTextureSeed = 1;
  bool hairInterpolation = false;
};

}  // namespace hirsute
