#include "hirsute/viewer/view/view_lighting.h"

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
