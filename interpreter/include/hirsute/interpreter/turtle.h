// The turtle: interprets a module string (after the homomorphism) into the Scene, as cpfg's
// interpreter does (cpfg-features.md (d)). It is a ModuleSink, so Derivation::emit() feeds it.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/interpreter/environment_queries.h"
#include "hirsute/interpreter/generalized_cylinder.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/turtle_state.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/model_checks.h"
#include "hirsute/lsys/module_sink.h"
#include "hirsute/core/progress.h"

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
  // A module of the source string: knows whether it came unchanged from the string (see
  // setSourceString).
  void module(ModuleRef m) override;
  void beginSource(std::size_t position) override { source_ = position; }
  // Closes what is open (a pending segment, polygons, a tube) at the end of the string.
  void finish();

  // The string whose modules reach the turtle (Derivation::mutableString()). cpfg ignores a `%`
  // made by the homomorphism, so `%` cuts only when it comes from this string; in query mode
  // (scene null) ?P ?H ?L ?U write into the module of this string they came from.
  void setSourceString(ModuleString* string) { sourceString_ = string; }

  // The program's string table (Program::strings): @L's first parameter is an id in it
  // (takesStringArgument). Without a table a label is its parameters printed as %g.
  void setStrings(const std::vector<std::string>* strings) { strings_ = strings; }

  // In query mode, every ?E goes to `environment` (null: ?E does nothing).
  void setEnvironment(EnvironmentQueries* environment) { environment_ = environment; }

  // More vertices in the scene than this ends interpretation with GeometryLimitError.
  void setMaxVertices(std::size_t vertices);

  // Shows `interpreting: N%` of `modules` (the string's length) on `progress` (null: nothing).
  void setProgress(Progress* progress, std::size_t modules);

  const TurtleState& state() const { return state_; }

  // What the turtle drew, by kind: the ray parity test compares these with cpfg's primitives
  // (generalized cylinders are counted through Scene::cylinderSegments).
  struct Counts {
    std::size_t segments = 0;  // F and G segments (lines, or cylinders and cones)
    std::size_t polygons = 0;  // { } polygons
    std::size_t polygonTriangles = 0;
    std::size_t surfaces = 0;  // ~X surface instances
    std::size_t surfaceTriangles = 0;
  };
  const Counts& counts() const { return counts_; }

 private:
  // A segment begun by F or G, drawn when the next node closes it (cpfg's EndNode): its end
  // width is the width at that time.
  struct PendingSegment {
    TurtleState start;
    bool open = false;
  };
  // What `[` saves besides the TurtleState (stack_ holds that, in step with this).
  struct BranchExtras {
    std::shared_ptr<GeneralizedCylinderBuilder::Saved> tube;
    bool subLsystem = false;  // pushed by ?(id,s) rather than [
  };
  // A polygon being collected between { and }.
  struct OpenPolygon {
    std::vector<glm::dvec3> vertices;
    int tubeType = 0;  // {(t): a generalized cylinder of type t instead (1 to 4)
    int strips = 4;    // {(t,strips)
    std::optional<TurtleState> firstPoint;  // closed tubes return to their first point at }
  };

  void dispatch(char symbol, const float* parameters, std::size_t count);
  void atModule(char first, char second, const float* parameters, std::size_t count);
  // `@` organ letter: the module of the organ at `organ` in organModuleTables().
  void organModule(int organ, char letter, const float* parameters, std::size_t count);
  // ?P ?H ?L ?U with `count` parameters (the values are the turtle's, not the module's).
  void query(char which, const float* parameters, std::size_t count);
  void environmentQuery(const float* parameters, std::size_t count);
  void move(double distance, bool draws, bool addsVertex);
  void closeSegment();
  void drawSegment(const TurtleState& start, const TurtleState& end);
  void pushBranch(bool subLsystem);
  void popBranch(bool subLsystem);
  void openPolygon(const float* parameters, std::size_t count);
  void closePolygon();
  void drawSurface(char id, const float* parameters, std::size_t count);
  void drawDisc(double diameter, const glm::dvec3& normal, bool ring);
  int material(int color) const;
  void warnOnce(const std::string& key, const std::string& message);
  // The text of @L(…): cpfg-manual.txt §6.10.
  std::string labelText(const float* parameters, std::size_t count);

  PendingSegment pending_;
  std::vector<BranchExtras> branchExtras_;
  std::vector<OpenPolygon> polygons_;
  std::string prefix_;  // @, @X, ~ or ? waiting for the module's last character
  // After `%` with `interpretation past %: off`: skipping the rest of the branch, through
  // skipDepth_ nested branches.
  bool skipping_ = false;
  std::size_t skipDepth_ = 0;
  bool fromSourceString_ = false;  // the module being handled came unchanged from sourceString_
  ModuleString* sourceString_ = nullptr;
  const std::vector<std::string>* strings_ = nullptr;
  EnvironmentQueries* environment_ = nullptr;
  std::set<std::string> warned_;
  Counts counts_;
  // Modules handled so far, and per organ the attribute record its last module made at which
  // count: a module of the organ right after it (three modules later: `@`, the organ's letter,
  // then the module's) changes that record in place rather than copying it.
  std::size_t modulesSeen_ = 0;
  std::size_t maxVertices_ = kDefaultMaxVertices;
  Progress* progress_ = nullptr;
  struct OrganScratch {
    int record = -1;
    std::size_t module = 0;
  };
  std::vector<OrganScratch> organScratch_;

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

// Interprets the derivation's current string into `scene` (homomorphism applied). Throws
// GeometryLimitError past `maxVertices`.
// Throws GeometryLimitError past `maxVertices`; shows its progress on `progress` when given.
void interpret(Derivation& derivation, const ModelResources& resources, Scene& scene,
               Diagnostics& diagnostics, std::size_t maxVertices = kDefaultMaxVertices,
               Progress* progress = nullptr);

// What the turtle makes of modules, for the checks of a model before it is derived
// (lsys/model_checks.h): the symbols it interprets and the `@` modules it knows.
ModuleMeanings turtleModuleMeanings();

// Installs the query pass: before each rewriting, the turtle walks the string and fills the
// parameters of ?P ?H ?L ?U with its position, heading, left and up vectors.
// With `environment`, the same pass also hands every ?E to it (cpfg -e).
void installQueryPass(Derivation& derivation, const ModelResources& resources,
                      Diagnostics& diagnostics, EnvironmentQueries* environment = nullptr);

}  // namespace hirsute
