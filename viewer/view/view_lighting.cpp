#include "hirsute/viewer/view/view_lighting.h"

#include <algorithm>
#include <cmath>

namespace hirsute {

ViewLighting viewLighting(const ViewSettings& view, bool materialMode,
                          const glm::vec3& towardsEye) {
  ViewLighting lighting;
  lighting.colorMap = !materialMode;
  lighting.colorMapLight = glm::length(view.lightDirection) > 0
                               ? glm::normalize(view.lightDirection)
                               : glm::vec3(1, 0, 0);
  lighting.diffuseReflection = static_cast<float>(view.diffuseReflection);
  if (lighting.colorMap) {
    LightSource light;  // white, no ambient (OpenGL's light 0), from `light direction:`
    light.directional = true;
    light.vector = lighting.colorMapLight;
    lighting.lights = {light};
  } else if (!view.lights.empty()) {
    lighting.lights = view.lights;
  } else {
    // OpenGL's default light 0 is directional along +z in eye coordinates: from the eye,
    // wherever the eye is (cpfg sets no light without `light:` lines).
    LightSource light;
    light.vector = glm::length(towardsEye) > 0 ? glm::normalize(towardsEye) : glm::vec3(0, 0, 1);
    lighting.lights = {light};
    lighting.headlight = true;
  }
  return lighting;
}

glm::vec3 backgroundColor(const Scene& scene, bool materialMode) {
  if (scene.materials.empty()) return glm::vec3(0.0f);
  const Material& m = scene.materials.front();
  return materialMode ? m.emission : m.diffuse;
}

glm::vec3 organLight(const ViewLighting& lighting, const glm::vec3& towardsEye) {
  if (lighting.colorMap) return lighting.colorMapLight;
  if (!lighting.headlight && !lighting.lights.empty()) return lighting.lights.front().vector;
  return towardsEye;
}

}  // namespace hirsute

namespace hirsute {

SphereLight sphereLight(const TraceSettings& look, const Bounds& plant, const glm::vec3& fallback) {
  constexpr float kPi = 3.14159265358979323846f;
  SphereLight light;
  glm::vec3 towards = look.lightDirection.value_or(fallback);
  const float half = glm::radians(std::clamp(look.lightAngle, 0.01f, 179.0f)) / 2;
  const glm::vec3 e = look.lightIrradiance;
  if (!(glm::length(towards) > 0) || !(e.r + e.g + e.b > 0)) return light;
  towards = glm::normalize(towards);
  const float size = plant.empty() ? 1.0f : std::max(plant.diagonal(), 1e-6f);
  const float distance = 50 * size;
  light.present = true;
  light.centre = (plant.empty() ? glm::vec3(0.0f) : plant.center()) + distance * towards;
  light.radius = distance * std::sin(half);
  // A sphere of angular radius δ and radiance L gives E = π L sin²δ to a surface facing it.
  light.radiance = e / (kPi * std::sin(half) * std::sin(half));
  return light;
}

glm::vec3 traceLightFallback(const ViewLighting& lighting, const Bounds& plant,
                             const glm::vec3& towardsEye) {
  if (lighting.colorMap) return lighting.colorMapLight;
  if (!lighting.headlight && !lighting.lights.empty()) {
    const LightSource& first = lighting.lights.front();
    return first.directional ? first.vector : first.vector - plant.center();
  }
  return towardsEye;
}

int litPaletteOffset(const ViewSettings& view, bool materialMode, bool colorMapFile) {
  const RenderMode mode = view.renderMode;
  const bool shaded =
      mode == RenderMode::Flat || mode == RenderMode::Shaded || mode == RenderMode::Shadows;
  return materialMode || !colorMapFile || !shaded ? 0 : view.diffuseReflection;
}

int litPaletteEntry(int index, int offset, int count) {
  if (offset == 0 || count <= 0) return index;
  const int last = count - 1;
  const int bank = std::clamp(index, 0, last) / 256 * 256;
  return std::clamp(index + offset, bank, std::min(bank + 255, last));
}

std::vector<LightSource> exportedLights(const ViewSettings& view, bool materialMode,
                                        const glm::vec3& towardsEye) {
  if (materialMode) return viewLighting(view, true, towardsEye).lights;
  if (!view.lights.empty()) return view.lights;
  LightSource light;
  light.directional = true;
  light.vector = view.lightDirection;
  return {light};
}

const Material& materialOrDefault(const Scene& scene, int index) {
  static const Material kDefault{};
  if (index < 0 || static_cast<std::size_t>(index) >= scene.materials.size()) return kDefault;
  return scene.materials[static_cast<std::size_t>(index)];
}

}  // namespace hirsute
