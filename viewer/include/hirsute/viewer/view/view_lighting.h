// How a view lights its scene and what it is drawn against, as cpfg does it (manual §8.1.3–8.1.4):
// one rule, GL-free, read by the GL renderer and by every exporter that places lights
// (pov_writer.cpp), so that a render and an export of one model cannot be lit differently.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"

namespace hirsute {

struct ViewLighting {
  // Colour-map mode: cpfg shades by moving along the palette, `diffuse reflection:` entries at
  // most, by the cosine between the normal and `light direction:` (normalized; +x without one).
  bool colorMap = false;
  glm::vec3 colorMapLight{1, 0, 0};
  float diffuseReflection = 0;
  // The lights: in material mode the view's `light:` lines or, without any, OpenGL's light 0
  // shining along the line of sight from the eye; in colour-map mode one white directional light
  // from `light direction:` (what the palette shift stands for, for exporters that need lights).
  std::vector<LightSource> lights;
  bool headlight = false;  // lights is OpenGL's default light 0, placed at the eye
};

// The lighting of `view`; `towardsEye` is the direction from the scene to the eye (the default
// light's direction).
ViewLighting viewLighting(const ViewSettings& view, bool materialMode, const glm::vec3& towardsEye);

// The one light the organs that shade themselves (organ_drawing.h) take, as a direction
// towards it: the colour map's `light direction:`, the eye's with the default light, else the
// first `light:` line's.
glm::vec3 organLight(const ViewLighting& lighting, const glm::vec3& towardsEye);

// With a colour map, GL's flat and shaded modes shade a surface of colour c along the palette,
// from c - d facing away from the light to c + d facing it (d: `diffuse reflection:`). A
// renderer whose own light does that shading (the path tracer, POV-Ray) draws a lit surface in
// the colour GL gives it in full light: entry c + d of c's bank. The offset d, or 0 where GL
// draws entry c itself (material mode, an unlit render mode) and where the palette is not a
// colour map file's (`colorMapFile` false): the default palette's neighbours are other colours,
// not the same colour lit, so its entry c is kept.
int litPaletteOffset(const ViewSettings& view, bool materialMode, bool colorMapFile);
// Entry `index` moved by `offset`, kept within its bank of 256 and the palette's `count` entries.
int litPaletteEntry(int index, int offset, int count);

// The path tracer's spherical light (docs/trace.md, "Lights"), which the POV-Ray export's
// `--trace-lights` places too: far off (fifty times the plant's size) towards the view file's
// `trace light: D:`, sized to subtend its angle and bright enough to give its irradiance.
struct SphereLight {
  bool present = false;  // none when the direction or the irradiance is zero
  glm::vec3 centre{0.0f};
  float radius = 0;
  glm::vec3 radiance{0.0f};
};
SphereLight sphereLight(const TraceSettings& look, const Bounds& plant, const glm::vec3& fallback);

// Where the tracer's light comes from without a `trace light: D:` line: where the GL render's
// light comes from (in colour-map mode the `light direction:`, else the first `light:` line's),
// or, with the default light, the eye (`towardsEye`).
glm::vec3 traceLightFallback(const ViewLighting& lighting, const Bounds& plant,
                             const glm::vec3& towardsEye);

// cpfg takes the background from entry 0 of the palette: the colour of a colour map, the
// emission of a material file.
glm::vec3 backgroundColor(const Scene& scene, bool materialMode);

// The lights an exported scene (POV-Ray, Blender) lights the plant with. In material mode, by the
// rule the GL renderer follows: the view's `light:` lines or, without any, OpenGL's light 0 from
// the eye (`towardsEye`). In colour-map mode, where the preview shades along the palette instead
// of lighting, the view's `light:` lines when it has any, or else one white light from
// `light direction:`.
std::vector<LightSource> exportedLights(const ViewSettings& view, bool materialMode,
                                        const glm::vec3& towardsEye);

// The Scene's material `index`, or OpenGL's default material for an index it does not have.
const Material& materialOrDefault(const Scene& scene, int index);

}  // namespace hirsute
