// Everything a cpfg view file (.v) sets, with cpfg's defaults (cpfg-features.md (e)).
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/fibre_settings.h"
#include "hirsute/interpreter/organ_settings.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

enum class Projection { Parallel, Perspective };
enum class RenderMode { Wireframe, Filled, Flat, Interpolated, Shaded, Fast, Shadows };

struct LightSource {
  // LightSource{} is OpenGL's light 0: directional from +z, no ambient, white diffuse and
  // specular. A `light:` line starts from it with a white ambient instead (kLightLineAmbient).
  bool directional = true;              // V: direction, O: point at position
  glm::vec3 vector{0, 0, 1};            // direction (towards the light) or position
  glm::vec3 ambient{0.0f}, diffuse{1.0f}, specular{1.0f};
  // Spot (P: x y z exponent cutoff) and attenuation (T: constant linear quadratic).
  bool spot = false;
  glm::vec3 spotDirection{0, 0, -1};
  float spotExponent = 0, spotCutoff = 180;
  float constantAttenuation = 1, linearAttenuation = 0, quadraticAttenuation = 0;
};

// The ambient colour of a `light:` line without `A:` (manual §8.1.3: 1 1 1). cpfg's rayshade
// output confirms it: two `light: V:` lines give `light 2 2 2 ambient` (cpfg-GeneralizedCylinder).
inline constexpr float kLightLineAmbient = 1.0f;

// cpfg numbers tropisms and torques together from 1 (`@Ts(i,e)`); the turtle keeps one
// elasticity per tropism.
inline constexpr std::size_t kMaxTropisms = 8;

struct Tropism {
  glm::vec3 direction{0, 1, 0};  // T:
  float angle = 0;               // A: degrees (0: gravitropism-like bending towards T)
  float intensity = 1;           // I:
  float elasticity = 0;          // E:
  float elasticityStep = 0;      // S: default increment for @Ti/@Td
  bool torque = false;           // `torque:` instead of `tropism:`
};

struct TextureDeclaration {
  std::string file;              // F: resolved against the view file's folder
  char mode = 'm';               // E: m modulate, d decal, b blend
  bool perSurface = false;       // S: one mapping over the whole surface, not per patch
  float ratio = 1;               // R:
  bool magnifyLinear = false;    // H: n|l (manual: near)
  std::string minify = "n";      // L: n|l|mnn|mln|mnl|mll (`m` reads as mll; manual: near)
  SourceLocation where;          // the file name on its view-file line
};

struct SurfaceDeclaration {
  char id = 0;
  std::string file;                    // resolved against the view file's folder
  float size = 1;
  int sPrecision = 0, tPrecision = 0;  // 0: from the file
  int texture = 0;                     // 1-based, 0 none
  SourceLocation where;                // the file name on its view-file line
  // `mesh flow: X x y z`: the direction in the mesh file's coordinates its coat lies along
  // (docs/meshes.md); none: the direction in which its v grows.
  std::optional<glm::dvec3> flow;
};

struct ContourDeclaration {
  int id = 0;
  std::string file;                    // resolved against the view file's folder
  SourceLocation where;                // the file name on its view-file line
};

// `shadow map: size: n color: r g b offset: factor units` (render mode: shadows).
struct ShadowMap {
  int size = 1024;
  glm::vec3 color{0.2f, 0.2f, 0.4f};
  float offsetFactor = 5, offsetUnits = 10;
};

// The path tracer's lines (docs/trace.md): the paper's one spherical light and hemispherical
// sky (papers/002_0e0bce38b72f21dc.txt, Sec. 5), the colours light passes through, and how
// hairs scatter.
// `veins: COLOUR PATTERN ...`: the path tracer's procedural veins on the surfaces of a colour
// (docs/trace.md, "Veins"), as colour and as a bump map.
enum class VeinPattern : std::uint8_t {
  Splines,    // jittered points joined by splines, fanning from base to tip (the crocus's petals)
  Particles,  // traced by particles that merge on their way to the midrib (the cherry's leaves)
};

struct VeinSettings {
  int colour = 0;                       // the surfaces' colour index
  VeinPattern pattern = VeinPattern::Splines;
  std::optional<glm::vec3> veinColour;  // C: r,g,b; none: the surface's colour darkened
  int count = 0;                        // N: veins (splines) or particles; 0: the pattern's default
  float width = 0.012f;                 // W: the main veins' width, a share of the surface's length
  float bump = 0.5f;                    // B: the veins' height, a share of their width
  float strength = 1;                   // K: how far the colour goes to the veins' colour, 0–1
  std::uint32_t seed = 1;               // S:
};

// `subsurface: COLOUR M: mean free path H: thickness A: r,g,b`: light that walks inside the thin
// surfaces of a colour (subsurface.h in the tracer).
struct SubsurfaceSettings {
  int colour = 0;
  float meanFreePath = 0, thickness = 0;  // in the model's units
  std::optional<glm::vec3> albedo;        // single-scattering; none: from the colour
};

// `trace sun: E: elevation A: azimuth T: turbidity G: ground albedo B: on|off`: a physical sun
// and sky (sky_model.h in the tracer).
struct SunSkySettings {
  float elevation = 45;  // degrees above the horizon
  float azimuth = 0;     // degrees about `trace up:`, 0: behind the eye, 180: facing it
  float turbidity = 3;
  float groundAlbedo = 0.2f;
};

struct TraceSettings {
  // `trace light: D: x,y,z A: degrees I: r,g,b`: towards the light from the plant (none: the
  // first `light:` line's direction, or the eye's), the angle it subtends, and the irradiance it
  // gives a surface facing it.
  std::optional<glm::vec3> lightDirection;
  float lightAngle = 5;
  glm::vec3 lightIrradiance{2.5f};
  // `trace sky: r,g,b`: the sky's radiance over the hemisphere about `trace up: x,y,z`.
  glm::vec3 sky{0.35f};
  glm::vec3 up{0, 1, 0};
  // `translucency: COLOUR T`: the share T of the colour's diffuse light that passes through.
  std::vector<std::pair<int, float>> translucent;
  // `hair shading: B: backscatter R: roughness S: specular` (hair_bsdf.h).
  float hairBackscatter = 0.4f, hairRoughness = 0.25f, hairSpecular = 0.08f;
  // `fibre: ORGAN [N] MODEL ...` (fibre_settings.h); a later line for the same hairs replaces it.
  std::vector<FibreSettings> fibres;
  std::vector<VeinSettings> veins;  // one a colour; a later line for a colour replaces it
  std::vector<SubsurfaceSettings> subsurface;  // one a colour; a later line replaces it
  // `trace environment: FILE S: scale R: degrees`: an OpenEXR latitude-longitude map of the
  // sky's radiance, named as written, read beneath the view file's folder (environment_map.h).
  std::string environment, environmentFolder;
  SourceLocation environmentAt;  // the file name on its line
  float environmentScale = 1, environmentRotation = 0;
  std::optional<SunSkySettings> sun;
  // `B: on|off` of either: whether camera rays that miss the plant see that sky.
  bool skySeen = true;
  std::optional<glm::vec3> ground;  // `trace ground: r,g,b`: a ground plane of that albedo
  // The camera's lines; the command line's options override them.
  std::optional<float> exposure, aperture, focus;
  std::optional<std::string> tone, filter;
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
  float minZoom = 0.05f, maxZoom = 50;
  bool zBuffer = true;
  RenderMode renderMode = RenderMode::Filled;
  bool antialiasing = false;
  bool concavePolygons = false;
  ShadowMap shadowMap;

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

  // hirsute render --trace.
  TraceSettings trace;

  // Each organ's settings (organ_settings.h), by type: view.organ<NAMESettings>().
  OrganSettingsSet organs;
  template <class Settings>
  Settings& organ() {
    return organs.get<Settings>();
  }
  template <class Settings>
  const Settings& organ() const {
    return organs.get<Settings>();
  }

};

}  // namespace hirsute
