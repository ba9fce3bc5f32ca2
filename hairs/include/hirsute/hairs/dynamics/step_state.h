// The state of a coat's step as one set of vertices (feather_coat_simulation.h): every stem
// node, then every body vertex, then every vane corner, each with where it is at the start of
// the step and where the step would take it. A vane corner is carried by its node (its owner):
// whatever moves the node in the collisions moves the corner alike, and an impulse on the
// corner is the node's.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace hirsute::dynamics {

struct StepState {
  std::vector<Eigen::Vector3d> start, end;
  std::vector<double> inverseMass;  // 0: kinematic (anchors, the body); a corner: its node's
  std::vector<int> owner;           // the vertex itself, or a corner's node
  std::vector<std::array<int, 2>> corners;  // per stem node: its left and right corners, or -1

  // Moves the end of `v` (a node or a body vertex) and the corners it carries.
  void moveEnd(int v, const Eigen::Vector3d& by) {
    end[v] += by;
    if (v < static_cast<int>(corners.size()))
      for (int c : corners[v])
        if (c >= 0) end[c] += by;
  }
  // The mass a zone's motion gives `v`: a corner's is its node's.
  double weight(int v) const { return owner[v] == v ? 1 / inverseMass[v] : 0.0; }
};

}  // namespace hirsute::dynamics
