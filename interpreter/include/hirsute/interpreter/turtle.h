// The turtle: interprets a module string (after the homomorphism) into the Scene, as cpfg's
// interpreter does (cpfg-features.md (d)). It is a ModuleSink, so Derivation::emit() feeds it.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/turtle_state.h"
#include "hirsute/lsys/diagnostic.h"
#include "hirsute/lsys/module_sink.h"

namespace hirsute {

class Derivation;
class GeneralizedCylinderBuilder;

class Turtle : public ModuleSink {
 public:
  // `scene` receives the geometry; with `scene` null the turtle only moves (the query pass).
  Turtle(const ModelResources& resources, Scene* scene, Diagnostics& diagnostics);
  ~Turtle() override;

  using ModuleSink::module;
  void module(char symbol, const float* parameters, std::size_t count) override;
  void beginSource(std::size_t position) override { source_ = position; }
  // Closes what is open (a pending segment, polygons, a tube) at the end of the string.
  void finish();

  const TurtleState& state() const { return state_; }

 private:
  // (implementation state: the state stack, pending segment, polygon stack, multi-character
  // module prefix, the cylinder builder …)
  const ModelResources& resources_;
  Scene* scene_;
  Diagnostics& diagnostics_;
  TurtleState state_;
  std::vector<TurtleState> stack_;
  std::size_t source_ = 0;
  std::unique_ptr<GeneralizedCylinderBuilder> cylinders_;
};

// Interprets the derivation's current string into `scene` (homomorphism applied).
void interpret(Derivation& derivation, const ModelResources& resources, Scene& scene,
               Diagnostics& diagnostics);

// Installs the query pass: before each rewriting, the turtle walks the string and fills the
// parameters of ?P ?H ?L ?U with its position, heading, left and up vectors.
void installQueryPass(Derivation& derivation, const ModelResources& resources, Diagnostics& diagnostics);

}  // namespace hirsute
