// Generalized cylinders (@Gs @Gc @Ge, with @Gt @Gr @# @!): Hermite tubes between control
// points, as cpfg builds them (cpfg-generalized-cylinders.md §1–§4). The turtle hands every
// control point's state; the builder writes triangles and CylinderSegments into the Scene.
#pragma once

#include <memory>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/turtle_state.h"

namespace hirsute {

class GeneralizedCylinderBuilder {
 public:
  GeneralizedCylinderBuilder(const ModelResources& resources, Scene* scene);
  ~GeneralizedCylinderBuilder();

  // Segments that would take the scene past this many vertices throw GeometryLimitError.
  void setMaxVertices(std::size_t vertices);

  bool active() const;
  // cpfg's spline_flag 1: a tube started by @Gc rather than @Gs makes every F and f add a
  // control point with 4 strips, until @Ge (§1). False while no tube is active.
  bool addsPointsOnMoves() const;
  void start(const TurtleState& state);                   // @Gs
  void point(const TurtleState& state, int strips);       // @Gc(n); starts a tube when none is active
  void end(const TurtleState& state, int strips);         // @Ge(n)

  // `[` saves the tube state with the turtle, `]` restores it (a branch may fork a tube).
  struct Saved;
  std::shared_ptr<Saved> save() const;
  void restore(const std::shared_ptr<Saved>& saved);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hirsute
