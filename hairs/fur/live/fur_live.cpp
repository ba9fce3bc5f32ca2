#include "hirsute/hairs/fur/fur_live.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_settings.h"
#include "hirsute/hairs/fur/fur_stage.h"
#include "hirsute/hairs/fur/wetness_mask.h"

namespace hirsute {
namespace {

// A droplet's radius (in the surface's [0, 1] units) and wetness, sprayed or dropped by hand.
constexpr float kDropletRadius = 0.05f;
constexpr float kDropletWetness = 1.0f;
// The wetness lost per second while drying: dry in 10 s.
constexpr float kDryingRate = 0.1f;
// A gust: as strong as a strand's spring, for this long (seconds).
constexpr float kGustStrength = 60.0f;
constexpr float kGustSeconds = 0.6f;

enum Action : std::size_t { kSpray, kDry, kGust };

const LiveAction kActions[] = {
    {"droplets", "n", 'J', "spray 20 droplets at random on the fur"},
    {"dry", "o", 'Y', "let the fur dry (wetness fades over 10 s: curls return, clumps open) / stop"},
    {"gust", "", 'G', "a gust of wind through the fur"},
};

// The droplets J sprays.
constexpr std::size_t kSprayedByKey = 20;

}  // namespace

LiveFur::LiveFur(LiveOrganHost& host) : host_(host), lastStep_(host.now()) {}

void LiveFur::take(const Scene& scene, const ViewSettings& view) {
  view_ = &view;
  Scene previous = std::move(fur_);
  fur_ = Scene{};
  fur_.organ<FurPart>() = scene.organ<FurPart>();
  // The frame before's particles and wetness carry over (an animation keeps its wet patches
  // and drags its fur); the view gets them at once.
  const bool hadFur = !previous.organ<FurPart>().surfaces.empty();
  motion_.reset(fur_, hadFur ? &previous : nullptr);
  if (hadFur) host_.redraw(fur_);
  lastStep_ = host_.now();
}

bool LiveFur::step() {
  if (fur_.organ<FurPart>().surfaces.empty() || view_ == nullptr) return false;
  const auto now = host_.now();
  const float seconds = static_cast<float>(std::chrono::duration<double>(now - lastStep_).count());
  lastStep_ = now;
  const glm::vec3 force =
      view_->organ<FurSettings>().force + (gustLeft_ > 0 ? gust_ : glm::vec3(0.0f));
  const bool wasMoving = moving_;
  bool changed = false;
  if (moving_ || gustLeft_ > 0) {
    moving_ = motion_.step(fur_, seconds, force) || gustLeft_ > 0;
    gustLeft_ = std::max(0.0f, gustLeft_ - seconds);
    changed = true;
  }
  if (drying_) {
    drying_ = fur::dryFur(fur_, kDryingRate, seconds);
    changed = true;
  }
  if (changed || wasMoving != moving_) host_.redraw(fur_);
  return changed;
}

void LiveFur::act(std::size_t index, const LiveActionCall& call) {
  switch (index) {
    case kSpray:
      if (call.byKey) {
        spray(kSprayedByKey);
      } else {
        // NaN and negative counts spray none; a count past every limit stays past them
        // (sprayDroplets refuses it) without overflowing the conversion.
        const double count = call.numbers.front();
        spray(count > 0 ? static_cast<std::size_t>(std::min(count, 1e15)) : 0);
      }
      break;
    case kDry:
      // The key toggles; `dry on` and `dry off` set.
      if (call.byKey || call.words.empty() || (call.words.front() == "on") != drying_) toggleDrying();
      break;
    case kGust:
      gust(call.viewport);
      break;
    default:
      break;
  }
}

void LiveFur::toggleDrying() {
  drying_ = !drying_;
  lastStep_ = host_.now();
}

std::size_t LiveFur::spray(std::size_t count) {
  const std::size_t landed =
      sprayDroplets(fur_, count, kDropletRadius, kDropletWetness, spraySeed_++);
  if (landed > 0) host_.redraw(fur_);
  return landed;
}

bool LiveFur::pointAt(glm::vec2 point, glm::ivec2 viewport) {
  if (fur_.organ<FurPart>().surfaces.empty()) return false;
  const Camera c = host_.camera(viewport);
  glm::vec3 origin, direction;
  if (c.projection == Projection::Perspective) {
    const float t = std::tan(glm::radians(c.fieldOfViewY) * 0.5f);
    const float aspect =
        static_cast<float>(c.viewport.x) / static_cast<float>(std::max(c.viewport.y, 1));
    origin = c.eye;
    direction = glm::normalize(c.forward + point.x * t * aspect * c.right + point.y * t * c.up);
  } else {
    direction = c.forward;
    origin = c.eye + point.x * c.halfWidth * c.right + point.y * c.halfHeight * c.up;
  }
  const auto hit = fur::pickFur(fur_, origin, direction);
  if (!hit) return false;
  fur::blendDroplet(fur_.organ<FurPart>().surfaces[hit->surface], hit->uv, kDropletRadius,
                    kDropletWetness);
  host_.redraw(fur_);
  return true;
}

void LiveFur::gust(glm::ivec2 viewport) {
  if (view_ == nullptr) return;
  // Across the line of sight, from alternating sides.
  gust_ = (spraySeed_++ % 2 == 0 ? 1.0f : -1.0f) * kGustStrength * host_.camera(viewport).right;
  gustLeft_ = kGustSeconds;
  moving_ = true;  // the host steps moving organs
  lastStep_ = host_.now();
}

std::string LiveFur::status() const {
  const std::vector<FurSurface>& surfaces = fur_.organ<FurPart>().surfaces;
  if (surfaces.empty()) return {};
  return fmt::format("{} layers a surface{}{}", surfaces.front().layers,
                     drying_ ? "  drying" : "", moving_ ? "  moving" : "");
}

const LiveOrganType& furLive() {
  static const LiveOrganTypeOf<LiveFur> type(
      "fur", 'U', kActions, "a droplet of water on the fur where the mouse points");
  return type;
}

}  // namespace hirsute
