// `hirsute simulate`: the model's feathers simulated over the frames of its animation (or with
// the body still), one POV-Ray scene (and with --obj one OBJ) per frame, numbered so that the
// frames can be rendered in any order and in parallel (docs/dynamics.md, "hirsute simulate").
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "hirsute/core/output_target.h"
#include "hirsute/hairs/dynamics/coat_motion.h"
#include "hirsute/hairs/dynamics/coat_shingling.h"
#include "hirsute/hairs/dynamics/wind_field.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"
#include "hirsute/hairs/fur/fur_motion.h"
#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_settings.h"
#include "hirsute/hairs/fur/fur_stage.h"
#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/export/point_cache.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/interaction/animation_file.h"
#include "hirsute/viewer/interaction/define_editor.h"
#include "model_pipeline.h"
#include "simulate_options.h"

namespace hirsute::cli {
namespace {

namespace fs = std::filesystem;

// The model of each frame: the animation's derivation step, and the animated #define's value
// at that frame, put into the .l's text in memory (nothing is written beside the model; its
// includes and files stay where they were; messages name the user's file). The files are read
// once: a frame derives and builds its Scene from them (and compiles the changed text when a
// #define moves).
class FrameModels {
 public:
  FrameModels(const ModelOptions& model, const BuiltScene& first,
              std::vector<AnimationFrame> animation, std::optional<AnimatedDefine> define,
              int frames)
      : model_(model),
        resources_(first.resources),
        lsystem_(first.model),
        animation_(std::move(animation)),
        define_(std::move(define)),
        frames_(frames),
        meshFrames_(resources_.meshFrames() > 1 ? resources_.meshFrames() : 0) {
    if (define_) lsystemText_ = readText(model_.lsystemFile);
  }

  // Whether frame k (from 1) has a body of its own, else the one before stays.
  bool moves(int k) const {
    return k == 1 || static_cast<std::size_t>(k) <= animation_.size() || define_.has_value() ||
           static_cast<std::size_t>(k) <= meshFrames_;
  }

  // Frame k's scene; its moving meshes (mesh sequences) at their k-th frame.
  Scene build(int k, Diagnostics& diagnostics) {
    resources_.meshFrame = static_cast<std::size_t>(k - 1);
    ModelOptions options = model_;
    if (k > 1) options.terminalProgress = nullptr;
    if (!animation_.empty())
      options.stopAfter =
          animation_[std::min(static_cast<std::size_t>(k), animation_.size()) - 1].step;
    if (!define_) return growScene(options, lsystem_, resources_, diagnostics);
    const double t = frames_ > 1 ? static_cast<double>(k - 1) / (frames_ - 1) : 0.0;
    const double value = define_->from + t * (define_->to - define_->from);
    // The constant changes in the .l's text, not in a copy beside it: nothing is written into
    // the model's folder, and messages name the user's file.
    options.lsystemText = replaceDefineValues(
        lsystemText_,
        {{define_->name,
          formatDefineValue(define_->integer ? std::round(value) : value, define_->integer)}});
    return growScene(options, loadLsystem(options, diagnostics), resources_, diagnostics);
  }

 private:
  static std::string readText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  ModelOptions model_;
  ModelResources resources_;
  Model lsystem_;
  std::vector<AnimationFrame> animation_;
  std::optional<AnimatedDefine> define_;
  std::string lsystemText_;  // the .l as read, when a #define moves
  int frames_;
  std::size_t meshFrames_;  // the frames of its moving meshes; 0 when none moves
};

dynamics::SimulationParameters parametersFor(const FeatherDynamicsSettings& view,
                                             const SimulateOptions& o) {
  dynamics::SimulationParameters p = dynamics::simulationParametersOf(view);
  if (o.gravity.size() == 3) p.gravity = {o.gravity[0], o.gravity[1], o.gravity[2]};
  if (o.wind.size() == 3) p.wind.velocity = {o.wind[0], o.wind[1], o.wind[2]};
  if (o.gusts) p.wind.gustStrength = *o.gusts;
  if (o.gustScale) p.wind.gustScale = *o.gustScale;
  if (o.gustPeriod) p.wind.gustPeriod = *o.gustPeriod;
  if (o.gustSeed) p.wind.seed = static_cast<int>(*o.gustSeed);
  if (o.drag) p.dragCoefficient = *o.drag;
  if (o.segments) p.segmentsPerFeather = *o.segments;
  if (o.vaneCollisions) p.vaneCollisions = true;
  if (o.noVaneCollisions) p.vaneCollisions = false;
  if (o.noRestingContacts) p.restingContacts = false;
  // The vanes' count leaves out those that overlap where the coat is placed.
  p.findVaneOverlaps = o.countVaneIntersections;
  return p;
}

// The fur's part of a run (docs/fur.md, "Fur over time"): every strand's particle stepped under
// the force per unit mass (the view file's `fur force:` or --fur-force) plus the wind and its
// gusts (the feathers' wind field, times --fur-drag); droplets at their frames and the rain;
// drying from its frame. Its state lives in the drawn Scene's fur surfaces.
class FurRun {
 public:
  static constexpr double kDefaultDrag = 1;  // per second

  FurRun(const SimulateOptions& o, const FurSettings& view, const dynamics::WindParameters& wind,
         double frameTime)
      : wind_(wind),
        force_(o.furForce.size() == 3 ? glm::vec3(o.furForce[0], o.furForce[1], o.furForce[2])
                                      : view.force),
        drag_(o.furDrag.value_or(kDefaultDrag)),
        dryRate_(o.dry.value_or(0)),
        dryFrom_(o.dryFrom),
        seed_(o.dropSeed),
        frameTime_(frameTime) {
    for (const std::string& text : o.drops) falls_.push_back(*dropletFall(text, false));
    if (!o.rain.empty()) rain_ = dropletFall(o.rain, true);
  }

  // Every droplet the run lets fall and what it blends, against the limits of one spray: an
  // error naming the options, before any frame.
  std::optional<std::string> checkCosts(const Scene& scene, int frames) const {
    int mask = 0;
    for (const FurSurface& s : scene.organ<FurPart>().surfaces)
      mask = std::max(mask, s.wetnessSize);
    double droplets = 0, texels = 0;
    auto charge = [&](double count, float radius) {
      const double side = std::min<double>(mask, 2.0 * radius * mask + 2);
      droplets += count;
      texels += count * side * side;
    };
    for (const DropletFall& f : falls_)
      if (f.frame <= frames) charge(f.count, f.radius);
    if (rain_) charge(std::floor(rain_->count * frameTime_ * (frames - 1)), rain_->radius);
    const DropletLimits limits;
    if (droplets > 10'000'000 || texels > static_cast<double>(limits.texels)) {
      return fmt::format(
          "error: the run's droplets (--drop, --rain: {:.0f} over {} frames) would blend more "
          "than {} texels of the wetness masks (the limit); use fewer or smaller droplets, or "
          "fewer frames",
          droplets, frames, limits.texels);
    }
    return std::nullopt;
  }

  // Frame 1: the fur as the model grew it, and the droplets of frame 1.
  void start(Scene& scene) {
    motion_.reset(scene);
    dropped_ = fall(scene, 1);
  }

  // A new body for the frame: its fur takes the particles, velocities and wetness of `before`.
  void carry(Scene& scene, const Scene& before) { motion_.reset(scene, &before); }

  // A later frame: its droplets, a frame time of motion from `time`, drying.
  void advance(Scene& scene, int frame, double time) {
    dropped_ = fall(scene, frame);
    const dynamics::WindField& wind = wind_;
    const bool windy = drag_ > 0 && (wind.parameters().velocity.squaredNorm() > 0 ||
                                     wind.parameters().gustStrength > 0);
    motion_.step(scene, static_cast<float>(frameTime_), [&](const glm::vec3& root) {
      if (!windy) return force_;
      const Eigen::Vector3d w = wind.velocityAt(Eigen::Vector3d(root.x, root.y, root.z), time);
      return force_ + static_cast<float>(drag_) * glm::vec3(w.x(), w.y(), w.z());
    });
    if (dryRate_ > 0 && frame >= dryFrom_)
      fur::dryFur(scene, static_cast<float>(dryRate_), static_cast<float>(frameTime_));
  }

  // The frame's row of fur.csv.
  std::string row(int frame, double time, const Scene& scene, double seconds) const {
    const fur::FurMeasures m = fur::measureFur(scene, &motion_);
    return fmt::format("{},{:.6g},{},{:.6g},{:.6g},{:.6g},{},{:.6g},{:.4f}\n", frame, time,
                       dropped_, m.meanBend, m.largestBend, m.largestSpeed, m.wetTexels,
                       m.meanWetness, seconds);
  }

  std::size_t droplets() const { return droppedInAll_; }

 private:
  std::size_t fall(Scene& scene, int frame) {
    std::size_t landed = 0;
    auto spray = [&](std::size_t count, const DropletFall& f) {
      landed += sprayDroplets(
          scene, count, f.radius, f.wetness,
          seed_ + 7919u * static_cast<std::uint32_t>(frame) + static_cast<std::uint32_t>(landed));
    };
    for (const DropletFall& f : falls_)
      if (f.frame == frame) spray(static_cast<std::size_t>(f.count), f);
    if (rain_ && frame > 1) {
      owed_ += rain_->count * frameTime_;
      const double whole = std::floor(owed_);
      owed_ -= whole;
      spray(static_cast<std::size_t>(whole), *rain_);
    }
    droppedInAll_ += landed;
    return landed;
  }

  dynamics::WindField wind_;
  glm::vec3 force_;
  double drag_, dryRate_;
  int dryFrom_;
  std::uint32_t seed_;
  double frameTime_;
  std::vector<DropletFall> falls_;
  std::optional<DropletFall> rain_;
  double owed_ = 0;  // rain's droplets not yet fallen
  std::size_t dropped_ = 0, droppedInAll_ = 0;
  fur::FurMotion motion_;
};

// "frame-0007.pov": the frame's number, at least four digits, as many as the last frame needs.
std::string frameName(int frame, int frames, const char* extension) {
  const int digits = std::max(4, static_cast<int>(std::to_string(frames).size()));
  return fmt::format("frame-{:0{}d}{}", frame, digits, extension);
}

int badInput(Progress& progress, const std::string& text) {
  progress.clear();
  std::cerr << text << '\n';
  return kExitBadInput;
}

int runSimulate(SimulateOptions o) {
  using Clock = std::chrono::steady_clock;
  const auto started = Clock::now();
  Progress progress = Progress::onTerminal(stderr);
  o.model.terminalProgress = &progress;
  // The simulation starts from the coat as it grew and settles it by its own collisions.
  leaveStageOut(o.model, dynamics::coatShinglingStage());
  // cpfg's order is .l .v .a; a lone .a after the .l is the animation file.
  if (o.animation.empty() && fs::path(o.model.viewFile).extension() == ".a")
    std::swap(o.animation, o.model.viewFile);
  Diagnostics diagnostics(&std::cerr);

  // The frames of the animation: derivation steps; without one, the derived model, still.
  std::vector<AnimationFrame> animation;
  std::optional<AnimatedDefine> define;
  BuiltScene first;
  std::optional<FrameModels> models;
  int frames = 0;
  try {
    if (!o.animate.empty()) {
      define = animatedDefine(o.animate, o.model.lsystemFile);
      if (!define) {
        return badInput(progress,
                        "hirsute: error: --animate takes NAME=FROM:TO, a #define "
                        "constant of the .l and two numbers, found '" +
                            o.animate + "'");
      }
    }
    first.resources = loadResources(o.model, diagnostics);
    first.model = loadLsystem(o.model, diagnostics);
    if (!o.animation.empty()) {
      const AnimationSettings settings = readAnimationFile(o.animation, diagnostics);
      const int length =
          o.model.steps.value_or(first.model.program.lsystems.front().derivationLength);
      animation = animationFrames(settings, length);
      if (animation.empty())
        return badInput(progress, o.animation + ": error: the animation has no frames");
      if (animation.size() > kMaxAnimationFrames && !o.frames) {
        return badInput(progress, fmt::format("{}: error: the animation has more than {} frames "
                                              "(the limit); --frames N draws its first N",
                                              o.animation, kMaxAnimationFrames));
      }
    }
    // Without an animation file, a moving mesh's frames set the length of the run.
    const std::size_t meshFrames = first.resources.meshFrames();
    frames = o.frames.value_or(!animation.empty() ? static_cast<int>(animation.size())
                               : meshFrames > 1   ? static_cast<int>(meshFrames)
                                                  : 48);
    models.emplace(o.model, first, animation, define, frames);
    first.scene = models->build(1, diagnostics);
  } catch (const DiagnosticError& e) {
    return badInput(progress, e.diagnostic().text());
  } catch (const std::runtime_error& e) {
    progress.clear();
    std::cerr << e.what() << '\n';
    return kExitIoError;
  }
  const bool feathers = !first.scene.organ<FeatherPart>().feathers.empty();
  const bool furry = !first.scene.organ<FurPart>().surfaces.empty();
  if (!feathers && !furry) {
    return badInput(progress, o.model.lsystemFile +
                                  ": error: the model has no feathers or fur to simulate (@Fe, "
                                  "@Fi, a feather coat or @U fur; docs/dynamics.md, docs/fur.md)");
  }
  const FeatherDynamicsSettings& view = first.resources.view.organ<FeatherSettings>().dynamics;
  const dynamics::SimulationParameters parameters = parametersFor(view, o);
  const int substeps = o.substeps.value_or(view.substeps);

  std::error_code ec;
  fs::create_directories(o.output, ec);
  if (!fs::is_directory(o.output)) {
    progress.clear();
    std::cerr << o.output << ": error: cannot make the output folder"
              << (ec ? ": " + ec.message() : std::string()) << '\n';
    return kExitIoError;
  }
  // The folder is the user's (a link to it is followed); every name in it is the program's own,
  // created there without following a link (output_folder.h).
  std::optional<OutputFolder> outputs;
  try {
    outputs.emplace(o.output);
  } catch (const std::runtime_error& e) {
    progress.clear();
    std::cerr << e.what() << '\n';
    return kExitIoError;
  }

  PovOptions pov;
  pov.view = first.resources.view;
  pov.materialMode = first.resources.materialMode;
  pov.colorMapFile = first.resources.colorMapFile;
  pov.width = o.width;
  pov.height = o.height;
  // The camera is fitted once for all frames: to the first frame, and for an animation to its
  // middle and last frames too, so that a body that moves stays in view.
  Bounds fit = first.scene.bounds();
  if (frames > 1 && models->moves(2)) {
    const int used = define ? frames
                            : std::min(std::max(static_cast<int>(animation.size()),
                                                static_cast<int>(first.resources.meshFrames())),
                                       frames);
    for (const int k : {(used + 1) / 2, used}) {
      try {
        fit.add(models->build(k, diagnostics).bounds());
      } catch (const DiagnosticError& e) {
        return badInput(progress, e.diagnostic().text());
      }
    }
  }
  pov.fitBounds = fit;

  std::optional<dynamics::CoatMotion> motion;
  try {
    if (feathers) motion.emplace(first.scene, parameters);
  } catch (const std::invalid_argument& e) {
    return badInput(progress, o.model.lsystemFile + ": error: cannot simulate: " + e.what());
  }
  const double frameTime = 1.0 / o.fps;
  std::optional<FurRun> fur;
  if (furry) {
    fur.emplace(o, first.resources.view.organ<FurSettings>(), parameters.wind, frameTime);
    if (const auto error = fur->checkCosts(first.scene, frames))
      return badInput(progress, o.model.lsystemFile + ": " + *error);
  }
  if (const std::size_t crossing = motion ? motion->penetrations() : 0; crossing > 0) {
    return badInput(progress,
                    o.model.lsystemFile + ": error: the feathers' stems already meet or come " +
                        "nearer than the minimum separation in " + std::to_string(crossing) +
                        " places before the first step; space them out or lower `dynamics "
                        "thickness:` (docs/dynamics.md)");
  }

  // What each frame's steps did, committed with the last frame.
  std::string table =
      "frame,time,steps,substeps,retries,candidates,contacts,impulses,repulsions,"
      "impact_zones,penetrations,kept_near,calami_left,calami_crossed,calami_zoned,"
      "seconds,vane_candidates,vane_contacts,vane_penetrations,vane_intersections_left,"
      "resting_contacts,searches,searched_pairs,ccd_queries,net_contacts\n";
  std::string furTable =
      "frame,time,droplets,mean_bend,largest_bend,largest_speed,wet_texels,mean_wetness,"
      "seconds\n";
  const auto writeTables = [&]() -> int {
    try {
      if (motion) {
        OutputTarget csv(*outputs, "simulation.csv");
        std::fputs(table.c_str(), csv.stream());
        csv.commit();
      }
      if (fur) {
        OutputTarget csv(*outputs, "fur.csv");
        std::fputs(furTable.c_str(), csv.stream());
        csv.commit();
      }
    } catch (const std::runtime_error& e) {
      progress.clear();
      std::cerr << e.what() << '\n';
      return kExitIoError;
    }
    return 0;
  };
  dynamics::SimulationCounters before;
  // The vanes meeting in a frame's state: the check that none is left when they collide, and
  // what passed through when not, counted then only when asked (a search of the whole coat's
  // vanes a frame, as dear as the frame's steps on a coat without vanes).
  const bool countVanes = parameters.vaneCollisions || o.countVaneIntersections;
  std::size_t vaneIntersectionsLeft = 0;  // over every frame's state
  double simulating = 0;                  // seconds in the steps, apart from deriving and writing
  std::uint64_t written = 0;              // bytes of the frames' files
  Scene drawn = first.scene;
  try {
    if (fur) fur->start(drawn);
  } catch (const DiagnosticError& e) {
    return badInput(progress, o.model.lsystemFile + ": " + e.diagnostic().text());
  }
  // --pc2: the frames as one point cache, committed with its base mesh after the last frame.
  OutputGroup cacheFiles;
  std::optional<PointCacheWriter> cache;
  if (!o.pc2.empty()) {
    try {
      cache.emplace(o.pc2, frames, o.maxOutputBytes, &cacheFiles);
    } catch (const std::invalid_argument& e) {
      return badInput(progress, std::string("hirsute: error: --pc2 ") + e.what());
    } catch (const std::runtime_error& e) {
      progress.clear();
      std::cerr << e.what() << '\n';
      return kExitIoError;
    }
  }
  progress.begin("simulating", Progress::Unit::Steps, frames, "frames");
  for (int frame = 1; frame <= frames; ++frame) {
    progress.update(frame - 1);  // the frames done
    const auto frameStarted = Clock::now();
    const Scene* body = nullptr;
    Scene moved;
    // Frame 1 is the model as derived; each later frame is a frame time after it.
    if (frame > 1) {
      if (models->moves(frame)) {
        try {
          moved = models->build(frame, diagnostics);
        } catch (const DiagnosticError& e) {
          return badInput(progress, e.diagnostic().text());
        }
        body = &moved;
      }
      try {
        const auto stepping = Clock::now();
        if (motion) motion->advance(frameTime, substeps, body);
        if (fur) {
          if (body) fur->carry(moved, drawn);
          fur->advance(body ? moved : drawn, frame, (frame - 2) * frameTime);
        }
        simulating += std::chrono::duration<double>(Clock::now() - stepping).count();
      } catch (const DiagnosticError& e) {
        if (const int failed = writeTables(); failed != 0) return failed;
        return badInput(progress, o.model.lsystemFile + ": " + e.diagnostic().text());
      } catch (const dynamics::FrameMismatch& e) {
        return badInput(
            progress,
            fmt::format("{}: error: frame {}: {}",
                        o.animation.empty() ? o.model.lsystemFile : o.animation, frame, e.what()));
      } catch (const dynamics::StepFailure& e) {
        // The frames before it stay, and so do their rows of the table.
        if (const int failed = writeTables(); failed != 0) return failed;
        progress.clear();
        std::cerr << o.model.lsystemFile << ": error: frame " << frame << ": " << e.what()
                  << "; the frames before it and their rows of simulation.csv are written\n";
        return kExitBadInput;
      }
    }
    if (body) drawn = std::move(moved);
    if (!o.noFrames) {
      try {
        if (motion) motion->pose(drawn);
        // A frame's files (the scene, its OBJ and their side files) land together or not at all.
        OutputGroup files;
        PovOptions framePov = pov;
        framePov.group = &files;
        framePov.folder = &*outputs;
        writePov(drawn, framePov, outputs->pathOf(frameName(frame, frames, ".pov")));
        if (o.obj) {
          ObjOptions frameObj;
          frameObj.group = &files;
          frameObj.folder = &*outputs;
          writeObj(drawn, outputs->pathOf(frameName(frame, frames, ".obj")), frameObj);
        }
        // What the frames write, against --max-output-bytes: all of them estimated from the
        // first before it lands, so that a run that would fill the disc writes nothing; then
        // each frame, as a body that grows makes them larger.
        const std::uint64_t frameBytes = files.bytes();
        if (frame == 1 &&
            static_cast<double>(frameBytes) * frames > static_cast<double>(o.maxOutputBytes)) {
          return badInput(
              progress,
              fmt::format("hirsute: error: {} frames of {} bytes each (the first frame's files) "
                          "would write about {:.0f} bytes, more than --max-output-bytes {}; "
                          "write fewer frames or raise the limit",
                          frames, frameBytes, static_cast<double>(frameBytes) * frames,
                          o.maxOutputBytes));
        }
        if (written + frameBytes > o.maxOutputBytes) {
          if (const int failed = writeTables(); failed != 0) return failed;
          return badInput(progress,
                          fmt::format("hirsute: error: frame {}'s files would take what the run "
                                      "writes past --max-output-bytes {}; the frames before it "
                                      "and their rows of the tables are written",
                                      frame, o.maxOutputBytes));
        }
        written += frameBytes;
        files.commit();
      } catch (const std::invalid_argument& e) {
        return badInput(progress, o.model.lsystemFile + ": error: cannot export: " + e.what());
      } catch (const std::runtime_error& e) {
        progress.clear();
        std::cerr << e.what() << '\n';
        return kExitIoError;
      }
    }
    if (cache) {
      try {
        if (motion && o.noFrames) motion->pose(drawn);
        cache->addFrame(drawn);
      } catch (const std::invalid_argument& e) {
        return badInput(progress, std::string("hirsute: error: ") + e.what());
      } catch (const std::runtime_error& e) {
        progress.clear();
        std::cerr << e.what() << '\n';
        return kExitIoError;
      }
    }
    const double frameSeconds = std::chrono::duration<double>(Clock::now() - frameStarted).count();
    if (fur) furTable += fur->row(frame, (frame - 1) * frameTime, drawn, frameSeconds);
    if (!motion) continue;
    const dynamics::SimulationCounters& c = motion->simulation().counters();
    // Vanes that meet in the frame's state: 0 when they collide, what passed through when not;
    // an empty cell where they are not counted.
    std::string vanesLeft;
    if (countVanes) {
      const std::size_t count = motion->vaneIntersections();
      vaneIntersectionsLeft += count;
      vanesLeft = std::to_string(count);
    }
    table += fmt::format(
        "{},{:.6g},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.4f},{},{},{},{},{},{},{},{},{}\n",
        frame, motion->simulation().time(), c.steps - before.steps, c.substeps - before.substeps,
        c.retries - before.retries, c.candidates - before.candidates, c.contacts - before.contacts,
        c.impulses - before.impulses, c.repulsions - before.repulsions,
        c.impactZones - before.impactZones, c.penetrations - before.penetrations,
        c.keptNear - before.keptNear, c.calamiLeft - before.calamiLeft,
        c.calamiCrossed - before.calamiCrossed, c.calamiZoned - before.calamiZoned, frameSeconds,
        c.vaneCandidates - before.vaneCandidates, c.vaneContacts - before.vaneContacts,
        c.vanePenetrations - before.vanePenetrations, vanesLeft,
        c.restingContacts - before.restingContacts, c.searches - before.searches,
        c.searchedPairs - before.searchedPairs, c.ccdQueries - before.ccdQueries,
        c.netContacts - before.netContacts);
    before = c;
  }
  if (const int failed = writeTables(); failed != 0) return failed;
  if (cache) {
    try {
      cache->finish();
      cacheFiles.commit();
    } catch (const std::runtime_error& e) {
      progress.clear();
      std::cerr << e.what() << '\n';
      return kExitIoError;
    }
  }
  progress.clear();
  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  // The closing line: what was simulated, for how long of motion, in what time, and where it
  // went; the counts of the steps and contacts behind it with -v.
  std::optional<fur::FurMeasures> furAtEnd;
  if (fur) furAtEnd = fur::measureFur(drawn);
  std::string simulated;
  if (motion) simulated = fmt::format("{} feathers", motion->simulation().stems().size());
  if (fur)
    simulated += fmt::format("{}{} strands of fur", motion ? " and " : "", furAtEnd->strands);
  std::string folder = printableText(o.output);
  if (folder.empty() || folder.back() != '/') folder += '/';
  const double motionSeconds = (frames - 1) * frameTime;
  std::cout << fmt::format("simulated {} frame{} of {} ({} s of motion) in {} \u2192 {}\n", frames,
                           frames == 1 ? "" : "s", simulated,
                           motionSeconds < 100 ? fmt::format("{:.3g}", motionSeconds)
                                               : fmt::format("{:.0f}", motionSeconds),
                           durationText(seconds), folder);
  if (!o.model.verbose) return kExitOk;
  if (fur) {
    const fur::FurMeasures& m = *furAtEnd;
    std::cerr << fmt::format(
        "{} frames of fur ({} strands on {} surfaces) in {:.2f} s, {:.3f} s of it simulating: "
        "{} droplets; at the end a mean bend of {:.3g} fur lengths, {} texels wet\n",
        frames, m.strands, drawn.organ<FurPart>().surfaces.size(), seconds, simulating,
        fur->droplets(), m.meanBend, m.wetTexels);
  }
  if (!motion) return kExitOk;
  const dynamics::SimulationCounters& c = motion->simulation().counters();
  const dynamics::FeatherCoatSimulation& simulation = motion->simulation();
  const std::string overlaps =
      parameters.vaneCollisions || parameters.findVaneOverlaps
          ? fmt::format(
                ", {} pairs of segments whose vanes overlapped at the start left out ({} "
                "still at the end)",
                simulation.vaneOverlapsAtStart(), simulation.vaneOverlaps().size())
          : std::string();
  std::cerr << fmt::format(
      "{} frames of {} feathers ({} rooted on the body) in {:.2f} s, {:.3f} s of it simulating "
      "({:.1f} frames/s): {} steps, {} retried; {} candidates, {} contacts, {} impact zones; "
      "resting contacts {}: {:.0f} held a step, {:.1f} searches a step of {:.0f} pairs each, {} "
      "CCD queries, {} contacts past the resting stage; {} intersections found and undone, {} "
      "calamus crossings put into zones at the smallest "
      "step, {} left; vanes {}: {} vane candidates, {} vane contacts{}, {}\n",
      frames, simulation.stems().size(), motion->boundRoots(), seconds, simulating,
      frames > 1 ? (frames - 1) / std::max(simulating, 1e-9) : 0.0, c.substeps, c.retries,
      c.candidates, c.contacts, c.impactZones, parameters.restingContacts ? "on" : "off",
      static_cast<double>(c.restingContacts) / std::max<double>(c.substeps + c.retries, 1),
      static_cast<double>(c.searches) / std::max<double>(c.substeps + c.retries, 1),
      static_cast<double>(c.searchedPairs) / std::max<double>(c.searches, 1), c.ccdQueries,
      c.netContacts, c.penetrations, c.calamiZoned, motion->penetrations(),
      parameters.vaneCollisions ? "colliding" : "not colliding", c.vaneCandidates, c.vaneContacts,
      overlaps,
      countVanes ? std::to_string(vaneIntersectionsLeft) + " vane intersections left"
                 : std::string("vane intersections not counted"));
  return kExitOk;
}

}  // namespace

void registerSimulateCommand(CLI::App& app, Action& action) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* command = app.add_subcommand("simulate",
                                         "Simulate the model's feathers and fur (wind, gravity, "
                                         "collisions, droplets) over its animation "
                                         "and write a POV-Ray scene per frame");
  addSimulateOptions(*command, *options);
  command->callback([options, &action] { action = [options] { return runSimulate(*options); }; });
}

}  // namespace hirsute::cli
