// Steady wind plus gusts from seeded Perlin noise.
#include "hirsute/hairs/dynamics/wind_field.h"

namespace hirsute::dynamics {

WindField::WindField(const WindParameters& parameters) : parameters_(parameters) {
  for (int axis = 0; axis < 3; ++axis) {
    // Three independent fields, one per component; a few octaves give gusts within gusts.
    gusts_[axis].SetSeed(parameters.seed * 3 + axis);
    gusts_[axis].SetOctaveCount(3);
    gusts_[axis].SetFrequency(1.0);
  }
}

Eigen::Vector3d WindField::velocityAt(const Eigen::Vector3d& position, double time) const {
  Eigen::Vector3d air = parameters_.velocity;
  if (parameters_.gustStrength == 0) return air;
  // Gusts travel with the wind; where it is still they drift along a fourth direction of time.
  const Eigen::Vector3d carried = (position - parameters_.velocity * time) / parameters_.gustScale;
  const double drift = time / parameters_.gustPeriod;
  for (int axis = 0; axis < 3; ++axis) {
    // libnoise's Perlin values lie in about [-1, 1].
    air[axis] +=
        parameters_.gustStrength *
        gusts_[axis].GetValue(carried.x() + drift, carried.y() - drift, carried.z() + 0.5 * drift);
  }
  return air;
}

}  // namespace hirsute::dynamics
