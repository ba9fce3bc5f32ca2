// The turtle: cpfg's interpretation of a module string (cpfg-features.md (d), manual §6).
#include "hirsute/interpreter/turtle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string_view>

#include <fmt/format.h>

#include "cylinder_mesh.h"
#include "hirsute/core/characters.h"
#include "hirsute/core/memory_budget.h"
#include "hirsute/interpreter/cpfg_numbers.h"
#include "hirsute/interpreter/generalized_cylinder.h"
#include "hirsute/interpreter/organ_modules.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/printf_format.h"
#include "polygon_triangulation.h"
#include "surface_mesh.h"
#include "tropism.h"
#include "turtle_frame.h"

namespace hirsute {

namespace {

constexpr double kPi = 3.14159265358979323846;
// cpfg keeps every width at least this: `#(0)` in cpfg-Tropisms ends a cone at radius 5e-8.
constexpr double kMinimumWidth = 1e-7;
// @Gc and @Ge without a parameter, and F/f/. adding control points: 4 strips (cpfg's code; the
// manual says 1).
constexpr int kDefaultStrips = 4;
// What a vertex of a surface takes in the Scene and the outputs built from it: position, normal
// and texture coordinate (32 bytes), two triangles' indices (24), and the vectors' slack.
constexpr double kBytesPerVertex = 120;
// cpfg draws no segment shorter than this (squared length): cpfg-TexturedSurfaces draws its
// F(0.00456) and leaves out F(0.00113) and F(0.00016), the fractal ferns leave out every F(0).
constexpr double kMinimumSegmentLengthSquared = 1e-5;
// @! without a parameter.
constexpr int kDefaultSides = 8;

double radians(double degrees) {
  return degrees * kPi / 180;
}

double parameterOr(const float* parameters, std::size_t count, std::size_t i, double otherwise) {
  return i < count ? static_cast<double>(parameters[i]) : otherwise;
}

// `;` and `,` step the colour within its bank of 256 (cpfg-features.md (d)).
int stepColor(int color, int increment) {
  const int base = color >= 0 ? color / 256 * 256 : 0;
  return base + (((color - base + increment) % 256) + 256) % 256;
}

// The modules the turtle interprets on its own: the cases of Turtle::dispatch's switch, which
// reads this table first (a symbol left out of it means nothing to the turtle).
constexpr std::string_view kTurtleSymbols = "FfGg+-&^/\\|[]?$.{}#!;,%_~@";

// The `@` modules of Turtle::atModule, which reads this table first: `@` and `first` alone (with
// or without parameters) when `alone`, or `first` without parameters and then one of `seconds`
// ("*": any symbol). The organs' modules (`@H…`) are their tables' (organ_modules.h).
struct AtModuleFamily {
  char first;
  bool alone;
  std::string_view seconds;
};
constexpr AtModuleFamily kAtModules[] = {
    {'O', true, ""},     {'o', true, ""}, {'c', true, ""},       {'b', false, "oc"},
    {'v', true, ""},     {'R', true, ""}, {'M', true, ""},       {'G', false, "scetr"},
    {'#', true, ""},     {'!', true, ""}, {'T', true, "xfpsid"}, {'D', true, "id"},
    {';', true, ""},     {',', true, ""}, {'L', true, ""},       {'S', true, ""},
    {'P', true, "SCD"},  {'I', true, ""}, {'J', true, ""},       {'m', true, "*"},
    {'Z', true, ""},     {'Y', true, ""},  // ilsa's: nothing to draw
};

const AtModuleFamily* atModuleFamily(char first) {
  for (const AtModuleFamily& family : kAtModules) {
    if (family.first == first) return &family;
  }
  return nullptr;
}

// `@` `first` without parameters waits for a second letter.
bool isAtFamily(char first) {
  const AtModuleFamily* family = atModuleFamily(first);
  return (family != nullptr && !family->seconds.empty()) || organModuleTableIndex(first) >= 0;
}

bool isAtModule(char first, char second) {
  if (const int organ = organModuleTableIndex(first); organ >= 0) {
    return second != 0 && organModuleTables()[static_cast<std::size_t>(organ)]->knows(second);
  }
  const AtModuleFamily* family = atModuleFamily(first);
  if (family == nullptr) return false;
  if (second == 0) return family->alone;
  return family->seconds == "*" || family->seconds.find(second) != std::string_view::npos;
}

// kTurtleSymbols by symbol: dispatch reads it for every module.
constexpr std::array<bool, 128> kTurtleSymbolTable = [] {
  std::array<bool, 128> table{};
  for (char c : kTurtleSymbols) table[static_cast<unsigned char>(c)] = true;
  return table;
}();

bool isTurtleSymbol(char symbol) {
  const auto index = static_cast<unsigned char>(symbol);
  return index < kTurtleSymbolTable.size() && kTurtleSymbolTable[index];
}

int largestPowerOfTwoAtMost(int n) {
  int p = 1;
  while (p * 2 <= n) p *= 2;
  return p;
}

}  // namespace

Turtle::Turtle(const ModelResources& resources, Scene* scene, Diagnostics& diagnostics)
    : resources_(resources), scene_(scene), diagnostics_(diagnostics) {
  const ViewSettings& view = resources.view;
  state_.lineWidth = std::max(static_cast<double>(view.initialLineWidth), kMinimumWidth);
  state_.color = view.initialColor;
  state_.backColor = view.initialBackColor;
  state_.scale = view.initialScale;
  state_.cylinderSides = std::clamp(view.contourSides, 3, kMaxContourSides);
  for (std::size_t i = 0; i < view.tropisms.size() && i < state_.elasticity.size(); ++i) {
    state_.elasticity[i] = view.tropisms[i].elasticity;
  }
  state_.oldElasticity = view.initialElasticity;
  state_.previousUp = state_.up;
  organScratch_.resize(organModuleTables().size());
  if (scene_ != nullptr) {
    if (scene_->materials.empty()) scene_->materials = resources.palette;
    if (scene_->textures.empty()) scene_->textures = resources.textures;
    scene_->lineStyle = view.lineStyle;
    cylinders_ = std::make_unique<GeneralizedCylinderBuilder>(resources, scene_);
  }
}

Turtle::~Turtle() = default;

void Turtle::module(ModuleRef m) {
  float values[kMaxModuleParameters];
  const std::size_t count = m.parameterCount();
  for (std::size_t i = 0; i < count; ++i) values[i] = m.parameter(i);
  fromSourceString_ = sourceString_ != nullptr && m.bytes() == sourceString_->bytes() + source_;
  dispatch(m.symbol(), values, count);
  fromSourceString_ = false;
}

void Turtle::module(char symbol, const float* parameters, std::size_t count) {
  dispatch(symbol, parameters, count);
}

void Turtle::warnOnce(const std::string& key, const std::string& message) {
  if (!warned_.insert(key).second) return;
  // The module has no place in the user's files (the homomorphism may have made it); the
  // message names it, and Diagnostics prints it once however many interpretations repeat it.
  diagnostics_.warn(SourceLocation{std::make_shared<const std::string>("<derived string>"), 0, 0},
                    message);
}

int Turtle::material(int color) const {
  if (scene_ == nullptr || scene_->materials.empty()) return std::max(color, 0);
  return std::clamp(color, 0, static_cast<int>(scene_->materials.size()) - 1);
}

void Turtle::setProgress(Progress* progress, std::size_t modules) {
  progress_ = progress;
  // The homomorphism may make more modules than the string has: the share stops at 100%.
  if (progress_) progress_->begin("interpreting", Progress::Unit::Percent, static_cast<double>(modules));
}

void Turtle::setMaxVertices(std::size_t vertices) {
  maxVertices_ = vertices;
  if (cylinders_) cylinders_->setMaxVertices(vertices);
}

void Turtle::dispatch(char symbol, const float* p, std::size_t count) {
  // The geometry limit, checked every few modules (one module adds a bounded amount; tubes
  // check before they build).
  if (++modulesSeen_ % 64 == 0 && scene_ != nullptr) {
    if (scene_->vertexCount() > maxVertices_) {
      throw GeometryLimitError("the geometry grew past " + std::to_string(maxVertices_) +
                               " vertices (raise the limit with --max-vertices)");
    }
    if (progress_) progress_->update(static_cast<double>(modulesSeen_));
  }
  if (skipping_) {
    // After `%` with `interpretation past %: off`: the rest of the branch is not interpreted,
    // up to the `]` that closes it.
    if (symbol == '[') {
      ++skipDepth_;
      return;
    }
    if (symbol != ']') return;
    if (skipDepth_ > 0) {
      --skipDepth_;
      return;
    }
    skipping_ = false;
  }

  if (!prefix_.empty()) {
    // Multi-character modules are single-character modules in the string; the parameters
    // belong to the last one (`@Gc(4)` is `@`, `G`, `c(4)`).
    const std::string prefix = prefix_;
    if (prefix == "@") {
      if (count == 0 && isAtFamily(symbol)) {
        prefix_ = {'@', symbol};
        return;
      }
      prefix_.clear();
      closeSegment();
      atModule(symbol, 0, p, count);
      return;
    }
    prefix_.clear();
    if (prefix[0] == '@') {
      closeSegment();
      atModule(prefix[1], symbol, p, count);
    } else if (prefix == "~") {
      closeSegment();
      drawSurface(symbol, p, count);
    } else {
      query(symbol, p, count);
    }
    return;
  }

  if (!isTurtleSymbol(symbol)) return;  // every other module means nothing to the turtle
  const ViewSettings& view = resources_.view;
  const double angle = radians(parameterOr(p, count, 0, view.angleIncrement));
  const double step = parameterOr(p, count, 0, 1) * state_.scale;
  switch (symbol) {
    case 'F':
      move(step, true, true);
      break;
    case 'f':
      move(step, false, true);
      break;
    case 'G':
      move(step, true, false);
      break;
    case 'g':
      move(step, false, false);
      break;
    // ABOP §1.5 with cpfg's signs: `+` turns left about U (H ← H·cos + L·sin), `&` pitches
    // down about L (H towards U), `/` rolls right about H (L ← L·cos + U·sin).
    case '+':
      rotatePair(state_.heading, state_.left, angle);
      orthonormalize(state_);
      break;
    case '-':
      rotatePair(state_.heading, state_.left, -angle);
      orthonormalize(state_);
      break;
    case '&':
      rotatePair(state_.heading, state_.up, angle);
      orthonormalize(state_);
      break;
    case '^':
      rotatePair(state_.heading, state_.up, -angle);
      orthonormalize(state_);
      break;
    case '/':
      rotatePair(state_.left, state_.up, angle);
      orthonormalize(state_);
      break;
    case '\\':
      rotatePair(state_.left, state_.up, -angle);
      orthonormalize(state_);
      break;
    case '|':
      state_.heading = -state_.heading;
      state_.left = -state_.left;
      break;
    case '[':
      closeSegment();
      pushBranch(false);
      break;
    case ']':
      closeSegment();
      popBranch(false);
      break;
    case '?':
      if (count == 0) {
        prefix_ = "?";
      } else {
        // ?(id[,s]) … $: a sub-L-system's modules, drawn from the caller's state scaled by s.
        closeSegment();
        pushBranch(true);
        state_.scale *= parameterOr(p, count, 1, 1);
      }
      break;
    case '$':
      closeSegment();
      if (!branchExtras_.empty() && branchExtras_.back().subLsystem) {
        popBranch(true);
      } else {
        // Outside a sub-L-system, ABOP's `$`: roll about H until L is horizontal, U upwards
        // (the same frame as @v).
        rollToVertical(state_);
      }
      break;
    case '{':
      closeSegment();
      openPolygon(p, count);
      break;
    case '}':
      closeSegment();
      closePolygon();
      break;
    case '.': {
      closeSegment();
      const bool tube = !polygons_.empty() && polygons_.back().tubeType > 0;
      if (cylinders_ && (count > 0 || tube || cylinders_->addsPointsOnMoves())) {
        // `.(n)`: a control point with n strips (manual §6.7.3).
        const int strips = count > 0 ? std::max(1, truncated(p[0]))
                                     : (tube ? polygons_.back().strips : kDefaultStrips);
        if (tube && !polygons_.back().firstPoint) polygons_.back().firstPoint = state_;
        cylinders_->point(state_, strips);
      } else if (!polygons_.empty() && !tube) {
        polygons_.back().vertices.push_back(state_.position);
      }
      break;
    }
    case '#':
      state_.lineWidth = count > 0 ? p[0] * state_.scale
                                   : state_.lineWidth + view.lineWidthIncrement * state_.scale;
      state_.lineWidth = std::max(state_.lineWidth, kMinimumWidth);
      break;
    case '!':
      state_.lineWidth = count > 0 ? p[0] * state_.scale
                                   : state_.lineWidth - view.lineWidthIncrement * state_.scale;
      state_.lineWidth = std::max(state_.lineWidth, kMinimumWidth);
      break;
    case ';':
      state_.color = count > 0 ? truncated(p[0]) : stepColor(state_.color, view.colorIncrement);
      break;
    case ',':
      state_.color = count > 0 ? truncated(p[0]) : stepColor(state_.color, -view.colorIncrement);
      break;
    case '%':
      // cpfg: a `%` the homomorphism made is ignored; one from the string ends the branch only
      // with `interpretation past %: off` (the derivation already cut after it).
      if (fromSourceString_ && !view.interpretationPastCut) {
        closeSegment();
        skipping_ = true;
        skipDepth_ = 0;
      }
      break;
    case '_':
      state_.oldElasticity =
          count > 0 ? static_cast<double>(p[0]) : state_.oldElasticity + view.elasticityIncrement;
      break;
    case '~':
      if (count == 0) prefix_ = "~";
      break;
    case '@':
      if (count == 0) prefix_ = "@";
      break;
    default:
      // Every other module means nothing to the turtle (cpfg-features.md (d)).
      break;
  }
}

// Organ modules (@H…): the organ's table reads them (organ_modules.h). Each organ keeps its
// own scratch record for the copy-on-write of its attribute records.
void Turtle::organModule(int organ, char letter, const float* p, std::size_t count) {
  OrganScratch& scratch = organScratch_[static_cast<std::size_t>(organ)];
  OrganModuleCall call{
      p,
      count,
      resources_,
      state_,
      scene_,
      [this](const std::string& key, const std::string& message) { warnOnce(key, message); },
      scratch.record,
      scratch.module,
      modulesSeen_};
  organModuleTables()[static_cast<std::size_t>(organ)]->interpret(letter, call);
}

void Turtle::atModule(char first, char second, const float* p, std::size_t count) {
  if (const int organ = organModuleTableIndex(first); organ >= 0) {
    organModule(organ, second, p, count);
    return;
  }
  // @Z and @Y (ilsa) and unknown @ modules: nothing (`hirsute check` warns of the unknown ones).
  if (!isAtModule(first, second)) return;
  const ViewSettings& view = resources_.view;
  switch (first) {
    case 'O':
      if (scene_ != nullptr) {
        const double diameter = count > 0 ? p[0] * state_.scale : state_.lineWidth;
        scene_->spheres.push_back(Sphere{glm::vec3(state_.position),
                                         static_cast<float>(diameter / 2), material(state_.color)});
      }
      break;
    case 'o':
      drawDisc(count > 0 ? p[0] * state_.scale : state_.lineWidth, glm::dvec3(0.0), false);
      break;
    case 'c':
      drawDisc(count > 0 ? p[0] * state_.scale : state_.lineWidth, state_.up, false);
      break;
    case 'b':
      if (second == 'o' || second == 'c') {
        drawDisc(count > 0 ? p[0] * state_.scale : state_.lineWidth,
                 second == 'c' ? state_.up : glm::dvec3(0.0), true);
      }
      break;
    case 'v':
      rollToVertical(state_);
      break;
    case 'R':
      if (count >= 2) {
        glm::dvec3 heading(p[0], p[1], count >= 3 ? p[2] : 0.0f);
        if (glm::length(heading) == 0) break;
        heading = glm::normalize(heading);
        if (count >= 6 && glm::length(glm::cross(heading, glm::dvec3(p[3], p[4], p[5]))) > 0) {
          // The given up vector, made perpendicular to H; L = H × U.
          state_.heading = heading;
          state_.up = glm::normalize(glm::dvec3(p[3], p[4], p[5]));
          state_.left = glm::cross(state_.heading, state_.up);
          orthonormalize(state_);
        } else {
          turnHeadingTo(state_, heading);
        }
      }
      break;
    case 'M':
      if (count >= 2) state_.position = glm::dvec3(p[0], p[1], count >= 3 ? p[2] : 0.0f);
      break;
    case 'G': {
      const int strips = count > 0 ? std::max(1, truncated(p[0])) : kDefaultStrips;
      switch (second) {
        case 's':
          if (cylinders_) cylinders_->start(state_);
          break;
        case 'c':
          if (cylinders_) cylinders_->point(state_, strips);
          break;
        case 'e':
          if (cylinders_) cylinders_->end(state_, strips);
          break;
        case 't':
          if (count >= 1) state_.tangentParameter = {p[0], count >= 2 ? p[1] : p[0]};
          break;
        case 'r':
          if (count == 1) {
            state_.scaleRadiusTangents = p[0] != 0;
          } else if (count >= 2) {
            // (angle in degrees, length) → (cos·length, sin·length); two parameters set both.
            auto tangent = [](double a, double l) {
              return glm::dvec2(std::cos(radians(a)) * l, std::sin(radians(a)) * l);
            };
            state_.radiusTangent[0] = tangent(p[0], p[1]);
            state_.radiusTangent[1] = count >= 4 ? tangent(p[2], p[3]) : state_.radiusTangent[0];
          }
          break;
        default:
          break;
      }
      break;
    }
    case '#':
      state_.contour = count > 0 ? truncated(p[0]) : 0;
      break;
    case '!':
      state_.cylinderSides =
          count > 0 ? std::clamp(truncated(p[0]), 3, kMaxContourSides) : kDefaultSides;
      break;
    case 'T': {
      if (second == 'x') {
        state_.texture = count > 0 ? std::max(0, truncated(p[0])) : 0;
      } else if (second == 'f') {
        state_.previousUp = state_.up;  // @Tf: the current twist is accepted
      } else if (second == 'p') {
        removeTwist(state_);
      } else if (second == 's' || second == 'i' || second == 'd') {
        if (count == 0) break;
        const int id = truncated(p[0]);
        const std::size_t known = std::min(view.tropisms.size(), state_.elasticity.size());
        if (id < 1 || static_cast<std::size_t>(id) > known) {
          warnOnce("tropism " + std::to_string(id), "@T" + std::string(1, second) +
                                                        ": no tropism " + std::to_string(id) +
                                                        " in the view file");
          break;
        }
        double& e = state_.elasticity[static_cast<std::size_t>(id - 1)];
        const double step = parameterOr(
            p, count, 1, view.tropisms[static_cast<std::size_t>(id - 1)].elasticityStep);
        if (second == 's') e = parameterOr(p, count, 1, 0);
        if (second == 'i') e += step;
        if (second == 'd') e -= step;
      }
      // `@T(id,v)` (the manual's increment) does nothing in cpfg.
      break;
    }
    case 'D':
      if (second == 0) {
        if (count > 0) state_.scale = p[0];
      } else if (second == 'i' || second == 'd') {
        const double factor = parameterOr(p, count, 0, view.scaleMultiplier);
        if (second == 'i') state_.scale *= factor;
        if (second == 'd' && factor != 0) state_.scale /= factor;
      }
      break;
    case ';':
      state_.backColor = count > 0
                             ? truncated(p[0])
                             : stepColor(state_.backColor < 0 ? state_.color : state_.backColor,
                                         view.backColorIncrement);
      break;
    case ',':
      state_.backColor = count > 0
                             ? truncated(p[0])
                             : stepColor(state_.backColor < 0 ? state_.color : state_.backColor,
                                         -view.backColorIncrement);
      break;
    case 'L':
      if (scene_ != nullptr) {
        scene_->labels.push_back(
            Label{glm::vec3(state_.position), labelText(p, count), material(state_.color)});
      }
      break;
    case 'S':
      warnOnce("@S",
               "@S: cpfg runs the parameter as a shell command; Hirsute does not run commands");
      break;
    case 'P':
      warnOnce("@P",
               "@PS, @PC and @PD (surfaces defined in the L-system) are not supported; nothing is "
               "drawn");
      break;
    case 'I':
    case 'J':
    case 'm':
      warnOnce(std::string("@") + first,
               std::string("@") + first + ": cpfg's rayshade-only module is ignored");
      break;
    default:
      break;
  }
}

ModuleMeanings turtleModuleMeanings() {
  return ModuleMeanings{isTurtleSymbol, isAtFamily, isAtModule};
}

void Turtle::query(char which, const float* parameters, std::size_t count) {
  glm::dvec3 value(0.0);
  switch (which) {
    case 'P':
      value = state_.position;
      break;
    case 'H':
      value = state_.heading;
      break;
    case 'L':
      value = state_.left;
      break;
    case 'U':
      value = state_.up;
      break;
    case 'E':
      environmentQuery(parameters, count);
      return;
    case 'Q':
      return;  // environment programs (cpfg -e) answer these; the turtle has nothing to say
    default:
      warnOnce(std::string("?") + which, std::string("unknown query '?") + which + "'");
      return;
  }
  // The query pass writes into the derived string, into the module it came from; a query the
  // homomorphism made has no place there.
  if (scene_ != nullptr || !fromSourceString_) return;
  for (std::size_t i = 0; i < std::min<std::size_t>(count, 3); ++i) {
    sourceString_->setParameter(source_, i,
                                static_cast<float>(value[static_cast<glm::length_t>(i)]));
  }
}

void Turtle::environmentQuery(const float* parameters, std::size_t count) {
  if (scene_ != nullptr || environment_ == nullptr) return;
  EnvironmentQuery q;
  float following[kMaxModuleParameters];
  q.turtle = &state_;
  q.parameters = parameters;
  q.count = count;
  if (fromSourceString_) {
    // cpfg sends the module after the ?E in the string; `~` and `@` with the next character.
    q.position = source_;
    const ModuleString& s = *sourceString_;
    std::size_t next = s.next(source_);
    if (next < s.end()) {
      ModuleRef m = s.at(next);
      q.followingSymbols = std::string(1, m.symbol());
      if ((m.symbol() == '~' || m.symbol() == '@') && !m.hasParameters() && s.next(next) < s.end()) {
        m = s.at(s.next(next));
        q.followingSymbols += m.symbol();
      }
      q.followingCount = m.parameterCount();
      for (std::size_t i = 0; i < q.followingCount; ++i) following[i] = m.parameter(i);
      q.followingParameters = following;
    }
  }
  environment_->query(q);
}

void Turtle::move(double distance, bool draws, bool addsVertex) {
  closeSegment();
  const ViewSettings& view = resources_.view;
  // cpfg's movement_adjust: the tropisms bend the frame before the step, the old tropism of
  // `_` after it.
  if (!view.tropisms.empty()) applyTropisms(state_, view.tropisms);
  const TurtleState start = state_;
  state_.position += state_.heading * distance;
  if (state_.texture > 0 &&
      static_cast<std::size_t>(state_.texture) <= resources_.textures.size()) {
    // cpfg-generalized-cylinders.md §4: t grows by l/(π·w)·(W/H)/R while a texture is set.
    const Texture& texture = resources_.textures[static_cast<std::size_t>(state_.texture - 1)];
    const double ratio =
        static_cast<std::size_t>(state_.texture) <= view.textures.size() &&
                view.textures[static_cast<std::size_t>(state_.texture - 1)].ratio != 0
            ? view.textures[static_cast<std::size_t>(state_.texture - 1)].ratio
            : 1.0;
    if (state_.lineWidth > 0 && texture.width > 0 && texture.height > 0) {
      const double aspect = static_cast<double>(largestPowerOfTwoAtMost(texture.width)) /
                            largestPowerOfTwoAtMost(texture.height);
      state_.texCoordT += distance / (kPi * state_.lineWidth) * aspect / ratio;
    }
  }
  applyOldTropism(state_, glm::dvec3(view.tropismDirection));
  state_.previousUp = state_.up;
  if (draws) {
    pending_.start = start;
    pending_.open = true;
  }
  if (!addsVertex) return;
  const bool tube = !polygons_.empty() && polygons_.back().tubeType > 0;
  if (cylinders_ && (tube || cylinders_->addsPointsOnMoves())) {
    if (tube && !polygons_.back().firstPoint) polygons_.back().firstPoint = state_;
    cylinders_->point(state_, tube ? polygons_.back().strips : kDefaultStrips);
  } else if (!polygons_.empty() && !tube) {
    polygons_.back().vertices.push_back(state_.position);
  }
}

void Turtle::closeSegment() {
  if (!pending_.open) return;
  pending_.open = false;
  drawSegment(pending_.start, state_);
}

void Turtle::drawSegment(const TurtleState& start, const TurtleState& end) {
  if (scene_ == nullptr) return;
  const glm::dvec3 axis = end.position - start.position;
  if (glm::dot(axis, axis) < kMinimumSegmentLengthSquared) return;
  ++counts_.segments;
  const double widthFrom = start.lineWidth;
  const double widthTo = resources_.view.taperedLines ? end.lineWidth : widthFrom;
  // The segment's colour is the one it started with (cpfg-MycelisSchematic: `;;F,,;!` is drawn
  // in the colour of `;;`).
  const int mat = material(start.color);
  if (resources_.view.lineStyle != LineStyle::Cylinder) {
    scene_->lines.push_back(LineSegment{glm::vec3(start.position), glm::vec3(end.position),
                                        static_cast<float>(widthFrom), static_cast<float>(widthTo),
                                        mat});
    return;
  }
  int texture = -1;
  if (resources_.materialMode && start.texture > 0 &&
      static_cast<std::size_t>(start.texture) <= scene_->textures.size()) {
    texture = start.texture - 1;
  }
  CylinderEnds ends;
  ends.from = start.position;
  ends.to = end.position;
  ends.radiusFrom = widthFrom / 2;
  ends.radiusTo = widthTo / 2;
  ends.left = start.left;
  ends.up = start.up;
  ends.sides = start.cylinderSides;
  ends.textureFrom = start.texCoordT;
  ends.textureTo = end.texCoordT;
  appendCylinder(scene_->meshFor(mat, texture), ends);
}

void Turtle::pushBranch(bool subLsystem) {
  stack_.push_back(state_);
  branchExtras_.push_back(BranchExtras{cylinders_ ? cylinders_->save() : nullptr, subLsystem});
}

void Turtle::popBranch(bool subLsystem) {
  if (stack_.empty()) {
    warnOnce(subLsystem ? "$" : "]",
             subLsystem ? "'$' without a sub-L-system to end" : "']' without a matching '['");
    return;
  }
  state_ = stack_.back();
  stack_.pop_back();
  if (cylinders_) cylinders_->restore(branchExtras_.back().tube);
  branchExtras_.pop_back();
}

void Turtle::openPolygon(const float* p, std::size_t count) {
  OpenPolygon polygon;
  const int type = count > 0 ? truncated(p[0]) : 0;
  if (type != 0) {
    // {(t[,strips]): a generalized cylinder whose control points come from F, f and `.`
    // (cpfg-generalized-cylinders.md §1). Hirsute's builder draws Hermite tubes; the B-spline
    // types 3 and 4, which no model of the corpus uses, are drawn as Hermite ones.
    if (type < 1 || type > 4) {
      warnOnce("{type", "{(" + std::to_string(type) +
                            "): no such generalized cylinder type; read as a polygon");
    } else {
      if (type > 2)
        warnOnce("{bspline", "{(3) and {(4): B-spline cylinders are drawn as Hermite ones");
      polygon.tubeType = type;
      polygon.strips = count > 1 ? std::max(1, truncated(p[1])) : kDefaultStrips;
    }
  }
  polygons_.push_back(std::move(polygon));
}

void Turtle::closePolygon() {
  if (polygons_.empty()) {
    warnOnce("}", "'}' without a matching '{'");
    return;
  }
  OpenPolygon polygon = std::move(polygons_.back());
  polygons_.pop_back();
  if (polygon.tubeType > 0) {
    if (cylinders_ && cylinders_->active()) {
      // A closed tube returns to its first point (types 2 and 4).
      if (polygon.tubeType % 2 == 0 && polygon.firstPoint)
        cylinders_->point(*polygon.firstPoint, polygon.strips);
      cylinders_->end(state_, polygon.strips);
    }
    return;
  }
  if (scene_ == nullptr || polygon.vertices.size() < 3) return;
  ++counts_.polygons;
  const PolygonTriangulation triangulation = triangulatePolygon(polygon.vertices);
  if (triangulation.triangles.empty()) return;
  // Filled with the colour current at `}` (manual §6.5).
  TriangleMesh& mesh = scene_->meshFor(material(state_.color));
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  const auto firstIndex = static_cast<std::uint32_t>(mesh.indices.size());
  for (const glm::dvec3& v : polygon.vertices) {
    mesh.positions.push_back(glm::vec3(v));
    mesh.normals.push_back(glm::vec3(triangulation.normal));
  }
  for (const auto& t : triangulation.triangles) {
    mesh.indices.insert(mesh.indices.end(), {base + t[0], base + t[1], base + t[2]});
  }
  counts_.polygonTriangles += triangulation.triangles.size();
  scene_->markThin(mesh, firstIndex);
  if (!state_.organs.none()) {
    OrganSurface record;
    record.kind = OrganSurfaceKind::Polygon;
    record.mesh = static_cast<int>(&mesh - scene_->meshes.data());
    record.firstVertex = base;
    record.firstIndex = firstIndex;
    record.indexCount = static_cast<std::uint32_t>(mesh.indices.size()) - firstIndex;
    record.uv = polygonPlaneCoordinates(polygon.vertices, triangulation.normal);
    record.organs = state_.organs;
    scene_->organSurfaces.push_back(std::move(record));
  }
}

void Turtle::drawSurface(char id, const float* p, std::size_t count) {
  const auto found = resources_.surfaces.find(id);
  if (found == resources_.surfaces.end()) {
    std::string key = "~";
    key += id;
    warnOnce(key, fmt::format("{}: the view file declares no surface '{}'", key, id));
    return;
  }
  const Surface& surface = found->second;
  SurfacePlacement placement;
  placement.position = state_.position;
  placement.heading = state_.heading;
  placement.left = state_.left;
  placement.up = state_.up;
  placement.frame = resources_.meshFrame;
  // ~X(s) scales uniformly (a second parameter is ignored), ~X(sx,sy,sz) per axis.
  placement.scale =
      count >= 3 ? glm::dvec3(p[0], p[1], p[2]) : glm::dvec3(parameterOr(p, count, 0, 1));
  placement.scale *= state_.scale;
  // cpfg writes no surface scaled to nothing (cpfg-gs-01-Lychnis's batch run, where every
  // ~l(0,0,0) is missing from the rayshade output).
  if (scene_ != nullptr && placement.scale != glm::dvec3(0.0)) {
    SurfaceAppearance appearance;
    appearance.material = [this](int patchColor) {
      return material(patchColor != 0 ? patchColor : state_.color);
    };
    // A texture named on the view file's `surface:` line is fixed; otherwise @Tx's applies
    // (manual §6.7.4). Textures are used in material mode only.
    const int texture = surface.texture > 0 ? surface.texture : state_.texture;
    if (resources_.materialMode && texture > 0 &&
        static_cast<std::size_t>(texture) <= scene_->textures.size()) {
      appearance.texture = texture - 1;
      const auto& declarations = resources_.view.textures;
      appearance.perSurfaceTexture = static_cast<std::size_t>(texture) <= declarations.size() &&
                                     declarations[static_cast<std::size_t>(texture - 1)].perSurface;
    }
    // A surface's tessellation is counted before it is built: PRECISION S: 1000 T: 1000 makes
    // a million vertices a patch.
    const std::size_t vertices =
        surface.mesh ? surface.mesh->positions.size()
                     : surface.patches.size() *
                           (static_cast<std::size_t>(std::max(1, surface.sPrecision)) + 1) *
                           (static_cast<std::size_t>(std::max(1, surface.tPrecision)) + 1);
    if (surface.mesh && (vertices > maxVertices_ || scene_->vertexCount() > maxVertices_ - vertices)) {
      throw GeometryLimitError(fmt::format(
          "surface ~{} (a mesh of {} vertices) would grow the geometry past {} vertices (raise "
          "the limit with --max-vertices)",
          surface.id, vertices, maxVertices_));
    }
    if (vertices > maxVertices_ || scene_->vertexCount() > maxVertices_ - vertices) {
      throw GeometryLimitError(fmt::format(
          "surface ~{} ({} patches at precision {} × {}) would grow the geometry past {} vertices "
          "(lower its precision, or raise the limit with --max-vertices)",
          surface.id, surface.patches.size(), std::max(1, surface.sPrecision),
          std::max(1, surface.tPrecision), maxVertices_));
    }
    // Within the vertex limit, the geometry may still need more memory than this process may
    // take (a machine, or a ulimit, smaller than the limit assumes): say so before building.
    const double bytes = static_cast<double>(scene_->vertexCount() + vertices) * kBytesPerVertex;
    const std::size_t budget = memoryBudgetBytes();
    if (bytes > 0.8 * static_cast<double>(budget)) {
      const std::string what =
          surface.mesh ? fmt::format("a mesh of {} vertices", vertices)
                       : fmt::format("{} patches at precision {} × {}", surface.patches.size(),
                                     std::max(1, surface.sPrecision), std::max(1, surface.tPrecision));
      throw GeometryLimitError(fmt::format(
          "surface ~{} ({}) would grow the geometry to {} vertices, some {} of memory, more than "
          "this process may take ({}){}",
          surface.id, what, scene_->vertexCount() + vertices, memorySizeText(bytes),
          memorySizeText(static_cast<double>(budget)),
          surface.mesh ? "" : "; lower its precision"));
    }
    ++counts_.surfaces;
    counts_.surfaceTriangles +=
        appendSurface(*scene_, surface, placement, appearance, state_.organs);
  }
  // The turtle goes on from the surface's END POINT.
  state_.position = placeSurfacePoint(surface, placement, surface.endPoint);
}

void Turtle::drawDisc(double diameter, const glm::dvec3& normal, bool ring) {
  if (scene_ == nullptr) return;
  const int mat = material(state_.color);
  if (!ring) {
    scene_->discs.push_back(
        Disc{glm::vec3(state_.position), glm::vec3(normal), static_cast<float>(diameter / 2), mat});
    return;
  }
  // @bc and @bo: a ring of outer diameter d and the line width across. A screen-aligned ring
  // faces the viewpoint of the view file.
  glm::dvec3 a, b;
  if (glm::length(normal) > 0) {
    a = state_.left;
    b = state_.heading;  // L × H = U: the ring faces the turtle's up
  } else {
    const ViewSettings& view = resources_.view;
    glm::dvec3 toViewer = glm::dvec3(view.viewpoint) - glm::dvec3(view.viewReference);
    toViewer = glm::length(toViewer) > 0 ? glm::normalize(toViewer) : glm::dvec3(0, 0, 1);
    a = std::abs(toViewer.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    a = glm::normalize(a - toViewer * glm::dot(a, toViewer));
    b = glm::cross(toViewer, a);
  }
  const double outer = diameter / 2;
  const double inner = std::max(0.0, outer - state_.lineWidth);
  appendAnnulus(scene_->meshFor(mat), state_.position, a, b, inner, outer, state_.cylinderSides);
}

void Turtle::finish() {
  closeSegment();
  if (!polygons_.empty()) {
    warnOnce("{", std::to_string(polygons_.size()) +
                      " polygon(s) opened by '{' are not closed by '}'; cpfg does not draw them");
    polygons_.clear();
  }
  prefix_.clear();
  skipping_ = false;
}

std::string Turtle::labelText(const float* p, std::size_t count) {
  // cpfg: @L("format", p1, p2, …) prints the parameters through the format, as printf does. The
  // string is the first parameter's id in the program's string table.
  if (count > 0 && strings_ != nullptr && p[0] >= 0 && p[0] == std::floor(p[0]) &&
      p[0] < static_cast<float>(strings_->size())) {
    std::vector<double> values(p + 1, p + count);
    PrintfResult result = formatPrintf((*strings_)[static_cast<std::size_t>(p[0])], values.data(),
                                       static_cast<int>(values.size()));
    if (result.missingValues) {
      warnOnce("@L format",
               "@L: the format has more conversions than values; they are drawn as written");
    }
    if (result.fieldTooWide > 0) {
      warnOnce("@L field", "@L: the format asks for a field of " +
                               std::to_string(result.fieldTooWide) + " characters (the limit is " +
                               std::to_string(kMaxPrintfField) + "); it is drawn as written");
    }
    return std::move(result.text);
  }
  if (count > 0 && strings_ != nullptr) {
    warnOnce("@L string", "@L: the first parameter is not a string; the label shows the numbers");
  }
  std::string text;
  for (std::size_t i = 0; i < count; ++i) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", static_cast<double>(p[i]));
    if (!text.empty()) text += ' ';
    text += buffer;
  }
  return text;
}

void interpret(Derivation& derivation, const ModelResources& resources, Scene& scene,
               Diagnostics& diagnostics, std::size_t maxVertices, Progress* progress) {
  Turtle turtle(resources, &scene, diagnostics);
  turtle.setMaxVertices(maxVertices);
  turtle.setProgress(progress, derivation.string().moduleCount());
  turtle.setStrings(&derivation.program().strings);
  turtle.setSourceString(&derivation.mutableString());
  derivation.emit(turtle, true);
  turtle.finish();
  // cpfg (manual §8.1.4): background objects are drawn after the string is interpreted.
  for (const BackgroundScene& background : resources.backgroundScenes)
    appendBackgroundScene(background, scene);
}

void installQueryPass(Derivation& derivation, const ModelResources& resources,
                      Diagnostics& diagnostics, EnvironmentQueries* environment) {
  // cpfg (manual §6.9): with query modules in the L-system, the string is interpreted before
  // every step, and the queries take the turtle's values. `resources` and `diagnostics` must
  // outlive the derivation.
  derivation.setQueryPass([&resources, &diagnostics, environment](Derivation& d) {
    Turtle turtle(resources, nullptr, diagnostics);
    turtle.setSourceString(&d.mutableString());
    turtle.setEnvironment(environment);
    if (environment) environment->beginPass(d.mutableString(), d.stepsDone());
    d.emit(turtle, true);
    turtle.finish();
    if (environment) environment->endPass();
  });
}

}  // namespace hirsute
