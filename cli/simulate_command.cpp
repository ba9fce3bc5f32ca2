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
#include "hirsute/hairs/dynamics/coat_motion.h"
#include "hirsute/core/output_target.h"
#include "hirsute/interpreter/feather_part.h"
#include "hirsute/interpreter/feather_settings.h"
#include "hirsute/viewer/export/obj_writer.h"
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
        frames_(frames) {
    if (define_) lsystemText_ = readText(model_.lsystemFile);
  }

  // Whether frame k (from 1) has a body of its own, else the one before stays.
  bool moves(int k) const {
    return k == 1 || static_cast<std::size_t>(k) <= animation_.size() || define_.has_value();
  }

  Scene build(int k, Diagnostics& diagnostics) const {
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
  return p;
}

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
    frames = o.frames.value_or(animation.empty() ? 48 : static_cast<int>(animation.size()));
    models.emplace(o.model, first, animation, define, frames);
    first.scene = models->build(1, diagnostics);
  } catch (const DiagnosticError& e) {
    return badInput(progress, e.diagnostic().text());
  } catch (const std::runtime_error& e) {
    progress.clear();
    std::cerr << e.what() << '\n';
    return kExitIoError;
  }
  if (first.scene.organ<FeatherPart>().feathers.empty()) {
    return badInput(progress, o.model.lsystemFile +
                                  ": error: the model has no feathers to simulate (@Fe, @Fi or "
                                  "a feather coat; docs/dynamics.md)");
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

  PovOptions pov;
  pov.view = first.resources.view;
  pov.materialMode = first.resources.materialMode;
  pov.width = o.width;
  pov.height = o.height;
  // The camera is fitted once for all frames: to the first frame, and for an animation to its
  // middle and last frames too, so that a body that moves stays in view.
  Bounds fit = first.scene.bounds();
  if (frames > 1 && models->moves(2)) {
    const int used = define ? frames : std::min(static_cast<int>(animation.size()), frames);
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
    motion.emplace(first.scene, parameters);
  } catch (const std::invalid_argument& e) {
    return badInput(progress, o.model.lsystemFile + ": error: cannot simulate: " + e.what());
  }
  if (const std::size_t crossing = motion->penetrations(); crossing > 0) {
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
      "seconds\n";
  const auto writeTable = [&]() -> int {
    try {
      OutputTarget csv(fs::path(o.output) / "simulation.csv");
      std::fputs(table.c_str(), csv.stream());
      csv.commit();
    } catch (const std::runtime_error& e) {
      progress.clear();
      std::cerr << e.what() << '\n';
      return kExitIoError;
    }
    return 0;
  };
  const double frameTime = 1.0 / o.fps;
  dynamics::SimulationCounters before;
  double simulating = 0;  // seconds in the steps, apart from deriving and writing
  Scene drawn = first.scene;
  progress.begin("simulating", Progress::Unit::Steps, frames);
  for (int frame = 1; frame <= frames; ++frame) {
    progress.update(frame);
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
        motion->advance(frameTime, substeps, body);
        simulating += std::chrono::duration<double>(Clock::now() - stepping).count();
      } catch (const dynamics::FrameMismatch& e) {
        return badInput(
            progress,
            fmt::format("{}: error: frame {}: {}",
                        o.animation.empty() ? o.model.lsystemFile : o.animation, frame, e.what()));
      } catch (const dynamics::StepFailure& e) {
        // The frames before it stay, and so do their rows of the table.
        if (const int failed = writeTable(); failed != 0) return failed;
        progress.clear();
        std::cerr << o.model.lsystemFile << ": error: frame " << frame << ": " << e.what()
                  << "; the frames before it and their rows of simulation.csv are written\n";
        return kExitBadInput;
      }
    }
    if (body) drawn = std::move(moved);
    const fs::path folder(o.output);
    if (!o.noFrames) {
      try {
        motion->pose(drawn);
        // A frame's files (the scene, its OBJ and their side files) land together or not at all.
        OutputGroup files;
        PovOptions framePov = pov;
        framePov.group = &files;
        writePov(drawn, framePov, folder / frameName(frame, frames, ".pov"));
        if (o.obj) {
          ObjOptions frameObj;
          frameObj.group = &files;
          writeObj(drawn, folder / frameName(frame, frames, ".obj"), frameObj);
        }
        files.commit();
      } catch (const std::invalid_argument& e) {
        return badInput(progress, o.model.lsystemFile + ": error: cannot export: " + e.what());
      } catch (const std::runtime_error& e) {
        progress.clear();
        std::cerr << e.what() << '\n';
        return kExitIoError;
      }
    }
    const dynamics::SimulationCounters& c = motion->simulation().counters();
    table += fmt::format(
        "{},{:.6g},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.4f}\n", frame,
        motion->simulation().time(), c.steps - before.steps, c.substeps - before.substeps,
        c.retries - before.retries, c.candidates - before.candidates, c.contacts - before.contacts,
        c.impulses - before.impulses, c.repulsions - before.repulsions,
        c.impactZones - before.impactZones, c.penetrations - before.penetrations,
        c.keptNear - before.keptNear, c.calamiLeft - before.calamiLeft,
        c.calamiCrossed - before.calamiCrossed, c.calamiZoned - before.calamiZoned,
        std::chrono::duration<double>(Clock::now() - frameStarted).count());
    before = c;
  }
  if (const int failed = writeTable(); failed != 0) return failed;
  progress.clear();
  const dynamics::SimulationCounters& c = motion->simulation().counters();
  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  std::cout << fmt::format(
      "{} frames of {} feathers ({} rooted on the body) in {:.2f} s, {:.3f} s of it simulating "
      "({:.1f} frames/s): {} steps, {} retried; {} candidates, {} contacts, {} impact zones; "
      "{} intersections found and undone, {} calamus crossings put into zones at the smallest "
      "step, {} left\n",
      frames, motion->simulation().stems().size(), motion->boundRoots(), seconds, simulating,
      frames > 1 ? (frames - 1) / std::max(simulating, 1e-9) : 0.0, c.substeps, c.retries,
      c.candidates, c.contacts, c.impactZones, c.penetrations, c.calamiZoned,
      motion->penetrations());
  return kExitOk;
}

}  // namespace

void registerSimulateCommand(CLI::App& app, Action& action) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Simulate the model's feathers (wind, gravity, collisions) over its animation and write a "
      "POV-Ray scene per frame");
  addSimulateOptions(*command, *options);
  command->callback([options, &action] { action = [options] { return runSimulate(*options); }; });
}

}  // namespace hirsute::cli
