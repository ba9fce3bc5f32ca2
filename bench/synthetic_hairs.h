// The benchmarks' synthetic hairy plant: seeded, so that every run and every benchmark draws and
// writes the same hairs. Hairs are placed directly, as instances of three templates, the way
// hairs/ places them on a model's generalized cylinders.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <random>
#include <string>
#include <vector>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::bench {

// Three templates of four segments (five turtle positions), straight to curled, in the hair's
// frame: x along the first segment.
inline std::vector<HairTemplate> syntheticHairTemplates() {
  std::vector<HairTemplate> result;
  for (int t = 0; t < 3; ++t) {
    HairTemplate hair;
    hair.file = "bench" + std::to_string(t) + ".l";
    hair.material = 1 + t;
    glm::vec3 p(0.0f), heading(1, 0, 0);
    std::vector<glm::vec3> polyline{p};
    float bend = 0.25f * static_cast<float>(t);
    for (int s = 0; s < 4; ++s) {
      p += heading * 0.25f;
      polyline.push_back(p);
      heading = glm::angleAxis(bend, glm::vec3(0, 0, 1)) * heading;
      hair.extent = std::max(hair.extent, glm::length(p));
    }
    hair.polylines.push_back(polyline);
    result.push_back(hair);
  }
  return result;
}

// `count` hairs on a fan of 24 stems: roots spread over each stem's surface, each hair pointing
// out of it and leaning up, turned about itself at random.
inline Scene syntheticHairScene(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  Scene scene;
  for (int i = 0; i < 4; ++i) {
    Material m;
    m.diffuse = m.ambient = glm::vec3(0.2f + 0.2f * static_cast<float>(i), 0.8f, 0.5f);
    scene.materials.push_back(m);
  }
  HairPart& part = scene.organ<HairPart>();
  part.templates = syntheticHairTemplates();
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  constexpr int kStems = 24;
  part.hairs.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    int stem = static_cast<int>(i * kStems / count);
    float fan = glm::radians(-60.0f + 120.0f * static_cast<float>(stem) / (kStems - 1));
    glm::vec3 axis(std::sin(fan), std::cos(fan), 0.3f * std::sin(3.0f * fan));
    axis = glm::normalize(axis);
    glm::vec3 side = glm::normalize(glm::cross(axis, glm::vec3(0, 0, 1)));
    glm::vec3 other = glm::cross(side, axis);
    float along = 6.0f * unit(random), around = glm::two_pi<float>() * unit(random);
    glm::vec3 normal = std::cos(around) * side + std::sin(around) * other;
    glm::vec3 direction = glm::normalize(normal + 0.6f * axis);
    Hair hair;
    hair.root = axis * along + 0.05f * normal;
    // The rotation from x onto the direction: the quaternion (1 + x·d, x × d), normalised.
    glm::vec3 turn = glm::cross(glm::vec3(1, 0, 0), direction);
    glm::quat point = glm::normalize(glm::quat(1 + direction.x, turn.x, turn.y, turn.z));
    hair.setRotation(point *
                     glm::angleAxis(glm::two_pi<float>() * unit(random), glm::vec3(1, 0, 0)));
    hair.length = 0.15f + 0.1f * unit(random);
    hair.radius = 0.004f;
    hair.templateIndex = static_cast<std::uint8_t>(i % 3);
    part.hairs.push_back(hair);
  }
  return scene;
}

}  // namespace hirsute::bench
