// The air's velocity around a feather coat: a steady wind plus seeded gusts, a smooth noise field
// carried along by the wind (Taylor's frozen turbulence) and drifting slowly in time
// (docs/dynamics.md, "Forces"). The noise is libnoise's coherent Perlin noise, one field per axis.
#pragma once

#include <libnoise/module/perlin.h>

#include <Eigen/Core>

namespace hirsute::dynamics {

struct WindParameters {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // the steady wind
  double gustStrength = 0;  // the largest speed a gust adds in each axis (about)
  double gustScale = 1;     // the size of a gust, world units
  double gustPeriod = 1;    // seconds over which the gust field changes where the wind is still
  int seed = 1;
};

class WindField {
 public:
  explicit WindField(const WindParameters& parameters);

  // The air's velocity at `position` and time `time`.
  Eigen::Vector3d velocityAt(const Eigen::Vector3d& position, double time) const;

  const WindParameters& parameters() const { return parameters_; }

 private:
  WindParameters parameters_;
  noise::module::Perlin gusts_[3];
};

}  // namespace hirsute::dynamics
