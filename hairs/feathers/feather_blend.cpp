#include "hirsute/hairs/feathers/feather_blend.h"

#include <algorithm>
#include <array>
#include <limits>
#include <set>

#include "hirsute/hairs/feathers/barb_interpolation.h"
#include "hirsute/hairs/feathers/bezier_curve.h"
#include "hirsute/hairs/feathers/default_barbs.h"
#include "hirsute/hairs/feathers/silhouette.h"

namespace hirsute {
namespace {

constexpr std::array<BarbSide, 2> kSides = {BarbSide::Left, BarbSide::Right};

float mix(float a, float b, float t) {
  return (1 - t) * a + t * b;
}

glm::vec3 mix(const glm::vec3& a, const glm::vec3& b, float t) {
  return (1 - t) * a + t * b;
}

std::vector<glm::vec3> mixVertices(std::span<const glm::vec3> a, std::span<const glm::vec3> b,
                                   float t) {
  const std::size_t count = std::max(a.size(), b.size());
  std::vector<glm::vec3> out = elevateBezierTo(a, count);
  const std::vector<glm::vec3> other = elevateBezierTo(b, count);
  for (std::size_t i = 0; i < count; ++i) out[i] = mix(out[i], other[i], t);
  return out;
}

float vaneAngle(const Vane& vane, float position) {
  return mix(vane.baseAngle, vane.tipAngle, position);
}

// The silhouette of a vane as points, a constant length as a flat one.
std::vector<SilhouettePoint> silhouetteOf(const Vane& vane) {
  if (!vane.silhouette.empty()) return vane.silhouette;
  return {{0, vane.barbLength}, {1, vane.barbLength}};
}

// Both silhouettes sampled at the positions of both, from below and above wherever either has a
// discontinuity, then mixed point by point: the result is the exact linear blend of the two
// piecewise-linear lengths.
std::vector<SilhouettePoint> mixSilhouettes(const std::vector<SilhouettePoint>& a,
                                            const std::vector<SilhouettePoint>& b, float t) {
  std::set<float> positions;
  std::set<float> steps;
  for (const auto* points : {&a, &b}) {
    for (std::size_t i = 0; i < points->size(); ++i) {
      positions.insert((*points)[i].position);
      if (i > 0 && (*points)[i].position == (*points)[i - 1].position) {
        steps.insert((*points)[i].position);
      }
    }
  }
  std::vector<SilhouettePoint> out;
  for (float position : positions) {
    if (steps.count(position)) {
      out.push_back({position, mix(silhouetteLength(a, position, true),
                                   silhouetteLength(b, position, true), t)});
    }
    out.push_back({position, mix(silhouetteLength(a, position), silhouetteLength(b, position), t)});
  }
  return out;
}

// For each key barb of the larger list (`many`), the index of its partner in the smaller
// (`few`): non-decreasing, from 0 to few.size() - 1, every index used, and of least total
// position difference (dynamic programming over the pairs).
std::vector<std::size_t> pairing(const std::vector<KeyBarb>& few,
                                 const std::vector<KeyBarb>& many) {
  const std::size_t m = few.size();
  const std::size_t n = many.size();
  constexpr double kNone = std::numeric_limits<double>::infinity();
  // cost[j][i]: the least cost of pairing many[0..j] with many[j] paired with few[i].
  std::vector<std::vector<double>> cost(n, std::vector<double>(m, kNone));
  const auto distance = [&](std::size_t i, std::size_t j) {
    return std::abs(double(few[i].position) - double(many[j].position));
  };
  cost[0][0] = distance(0, 0);
  for (std::size_t j = 1; j < n; ++j) {
    for (std::size_t i = 0; i < m && i <= j; ++i) {
      if (m - 1 - i > n - 1 - j) continue;  // the rest of `few` could not be used any more
      const double stay = cost[j - 1][i];
      const double step = i > 0 ? cost[j - 1][i - 1] : kNone;
      const double best = std::min(stay, step);
      if (best < kNone) cost[j][i] = best + distance(i, j);
    }
  }
  std::vector<std::size_t> out(n);
  std::size_t i = m - 1;
  for (std::size_t j = n; j-- > 0;) {
    out[j] = i;
    if (j > 0 && i > 0 && cost[j - 1][i - 1] <= cost[j - 1][i]) --i;
  }
  return out;
}

KeyBarb mixKeyBarbs(const KeyBarb& a, const Vane& vaneA, const KeyBarb& b, const Vane& vaneB,
                    BarbSide side, float t) {
  KeyBarb out;
  out.side = side;
  out.position = mix(a.position, b.position, t);
  out.vertices = mixVertices(a.vertices, b.vertices, t);
  if (a.angle || b.angle) {
    out.angle = mix(a.angle.value_or(vaneAngle(vaneA, a.position)),
                    b.angle.value_or(vaneAngle(vaneB, b.position)), t);
  }
  out.plumulaceous = mix(a.plumulaceous, b.plumulaceous, t);
  return out;
}

// What a feather has at the rachis base (0) or tip (1) of one vane, as a key barb: its
// key barb there, or the default Bdf1 (fully plumulaceous) at the base and Bdf2 at the tip.
KeyBarb grownBarbAtEnd(const std::vector<KeyBarb>& keys, float end) {
  if (end == 0) {
    // At the base the last of the key barbs at 0 counts (a barb exactly there takes it).
    const KeyBarb* found = nullptr;
    for (const KeyBarb& key : keys) {
      if (key.position == 0) found = &key;
    }
    if (found) return *found;
    KeyBarb down;
    down.vertices = {{0, 0, 0}, {1, 0, 0}};
    down.plumulaceous = 1;
    return down;
  }
  // At the tip the first key barb at 1 shapes the barbs below it.
  for (const KeyBarb& key : keys) {
    if (key.position == 1) return key;
  }
  KeyBarb tip;
  const std::span<const glm::vec3> bdf2 = pennaceousDefaultBarb();
  tip.vertices.assign(bdf2.begin(), bdf2.end());
  tip.position = 1;
  return tip;
}

// Sec. 4.2.3, Fig. 5: the key barbs of one vane of the blend.
void blendKeyBarbs(const FeatherType& a, const FeatherType& b, BarbSide side, float t,
                   std::vector<KeyBarb>& out) {
  std::vector<KeyBarb> keysA = VaneKeyBarbs(a, side).keys();
  std::vector<KeyBarb> keysB = VaneKeyBarbs(b, side).keys();
  if (keysA.empty() && keysB.empty()) return;
  // Down against key barbs: a fully plumulaceous copy of each.
  const auto downFor = [](std::vector<KeyBarb> keys) {
    for (KeyBarb& key : keys) {
      key.plumulaceous = 1;
      key.angle.reset();
    }
    return keys;
  };
  // Above its last key barb the keyed vane has Bdf2 where down has Bdf1: a key barb at the tip
  // pairs the two there too.
  const auto withTip = [](std::vector<KeyBarb> keys) {
    if (keys.back().position < 1) keys.push_back(grownBarbAtEnd(keys, 1));
    return keys;
  };
  if (keysA.empty()) {
    keysB = withTip(keysB);
    keysA = downFor(keysB);
  } else if (keysB.empty()) {
    keysA = withTip(keysA);
    keysB = downFor(keysA);
  }
  const bool aIsFewer = keysA.size() <= keysB.size();
  const std::vector<KeyBarb>& few = aIsFewer ? keysA : keysB;
  const std::vector<KeyBarb>& many = aIsFewer ? keysB : keysA;
  const std::vector<std::size_t> partner = pairing(few, many);
  for (std::size_t j = 0; j < many.size(); ++j) {
    const KeyBarb& fromA = aIsFewer ? few[partner[j]] : many[j];
    const KeyBarb& fromB = aIsFewer ? many[j] : few[partner[j]];
    out.push_back(mixKeyBarbs(fromA, a.vane(side), fromB, b.vane(side), side, t));
  }
}

// A key barb's control vertices moved evenly onto its chord: the barb straight, as in the sheath.
std::vector<glm::vec3> straightened(const std::vector<glm::vec3>& vertices) {
  std::vector<glm::vec3> out(vertices.size());
  const float last = static_cast<float>(vertices.size() - 1);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    out[i] = mix(vertices.front(), vertices.back(), static_cast<float>(i) / last);
  }
  return out;
}

// An extra straight key barb of growth at `position`: until age 0.8 straight with `angle`; in the
// last 20% (`rise` from 0 to 1) turning into `target`, the grown barb where it stands, its angle
// into the grown vane's.
KeyBarb extraKeyBarb(BarbSide side, float position, float angle, const KeyBarb& target,
                     float targetAngle, float rise) {
  KeyBarb extra;
  extra.side = side;
  extra.position = position;
  const std::vector<glm::vec3> straight = {{0, 0, 0}, {1, 0, 0}};
  extra.vertices = mixVertices(straight, target.vertices, rise);
  extra.plumulaceous = rise * target.plumulaceous;
  extra.angle = mix(angle, target.angle.value_or(targetAngle), rise);
  return extra;
}

// The share of the vane over which the sheath's front opens the barbs.
constexpr float kSheathEdge = 0.06f;

float ramp(float age, float start, float end) {
  return std::clamp((age - start) / (end - start), 0.0f, 1.0f);
}

// A type's textures as cross-fade layers: its own cross-fade, or its one texture (or none).
std::vector<FeatherTextureLayer> textureLayersOf(const FeatherAppearance& appearance) {
  if (!appearance.crossFade.empty()) return appearance.crossFade;
  return {FeatherTextureLayer{appearance.texture, appearance.textureMapping,
                              appearance.sceneTexture, 1.0f}};
}

// The cross-fade of two types' textures at t: each layer weighted by its type's share, equal
// layers merged; empty when both draw one and the same texture (or none), which needs no fading.
std::vector<FeatherTextureLayer> crossFadeOf(const FeatherAppearance& a,
                                             const FeatherAppearance& b, float t) {
  std::vector<FeatherTextureLayer> layers;
  auto add = [&layers](FeatherTextureLayer layer, float share) {
    layer.weight *= share;
    if (layer.texture.empty()) layer.mapping = FeatherTextureMapping::Barb;  // white everywhere
    auto same = std::find_if(layers.begin(), layers.end(), [&layer](const FeatherTextureLayer& l) {
      return l.texture == layer.texture && l.mapping == layer.mapping;
    });
    if (same != layers.end()) {
      same->weight += layer.weight;
    } else if (layer.weight > 0) {
      layers.push_back(std::move(layer));
    }
  };
  for (const FeatherTextureLayer& layer : textureLayersOf(a)) add(layer, 1 - t);
  for (const FeatherTextureLayer& layer : textureLayersOf(b)) add(layer, t);
  if (layers.size() <= 1) return {};
  return layers;
}

}  // namespace

FeatherType blendFeatherTypes(const FeatherType& a, const FeatherType& b, float t) {
  t = std::clamp(t, 0.0f, 1.0f);
  if (t == 0) return a;
  if (t == 1) return b;
  FeatherType out;
  out.calamusLength = mix(a.calamusLength, b.calamusLength, t);
  out.calamusWidthRatio = mix(a.calamusWidthRatio, b.calamusWidthRatio, t);
  out.rachisLength = mix(a.rachisLength, b.rachisLength, t);
  out.rachisWidth = mix(a.rachisWidth, b.rachisWidth, t);
  out.rachisSideCurvature = mix(a.rachisSideCurvature, b.rachisSideCurvature, t);
  out.rachisFrontCurvature = mix(a.rachisFrontCurvature, b.rachisFrontCurvature, t);
  out.barbSpacingBase = mix(a.barbSpacingBase, b.barbSpacingBase, t);
  out.barbSpacingTip = mix(a.barbSpacingTip, b.barbSpacingTip, t);
  for (BarbSide side : kSides) {
    const Vane& va = a.vane(side);
    const Vane& vb = b.vane(side);
    Vane& v = out.vane(side);
    v.baseAngle = mix(va.baseAngle, vb.baseAngle, t);
    v.tipAngle = mix(va.tipAngle, vb.tipAngle, t);
    v.barbLength = mix(va.barbLength, vb.barbLength, t);
    if (!va.silhouette.empty() || !vb.silhouette.empty()) {
      v.silhouette = mixSilhouettes(silhouetteOf(va), silhouetteOf(vb), t);
    }
    blendKeyBarbs(a, b, side, t, out.keyBarbs);
  }
  const FeatherType& nearer = t < 0.5f ? a : b;
  out.seed = nearer.seed;
  // Bdf1 blends with the shape: the two types' seeds, each with its weight in the blend.
  auto seedsOf = [](const FeatherType& type) {
    return type.seedBlend.empty() ? std::vector<std::pair<std::uint64_t, float>>{{type.seed, 1.0f}}
                                  : type.seedBlend;
  };
  for (const auto& [seed, weight] : seedsOf(a)) out.seedBlend.emplace_back(seed, (1 - t) * weight);
  for (const auto& [seed, weight] : seedsOf(b)) {
    const std::uint64_t key = seed;  // clang before 16 cannot capture a structured binding
    auto same = std::find_if(out.seedBlend.begin(), out.seedBlend.end(),
                             [key](const auto& entry) { return entry.first == key; });
    if (same != out.seedBlend.end()) {
      same->second += t * weight;
    } else {
      out.seedBlend.emplace_back(seed, t * weight);
    }
  }
  if (out.seedBlend.size() == 1) out.seedBlend.clear();  // one seed: its own table
  out.appearance = nearer.appearance;
  out.appearance.crossFade = crossFadeOf(a.appearance, b.appearance, t);
  if (a.appearance.colourKind == FeatherColourKind::Rgb &&
      b.appearance.colourKind == FeatherColourKind::Rgb) {
    out.appearance.colour = mix(a.appearance.colour, b.appearance.colour, t);
  }
  if (a.appearance.drawing == BarbStyle::Strips && b.appearance.drawing == BarbStyle::Strips) {
    out.appearance.stripWidth = mix(a.appearance.stripWidth, b.appearance.stripWidth, t);
  }
  if (a.afterfeather && b.afterfeather) {
    out.afterfeather =
        std::make_shared<const FeatherType>(blendFeatherTypes(*a.afterfeather, *b.afterfeather, t));
    out.afterfeatherSize = mix(a.afterfeatherSize, b.afterfeatherSize, t);
  } else if (a.afterfeather || b.afterfeather) {
    out.afterfeather = a.afterfeather ? a.afterfeather : b.afterfeather;
    out.afterfeatherSize = a.afterfeather ? (1 - t) * a.afterfeatherSize : t * b.afterfeatherSize;
  }
  return out;
}

FeatherType grownFeatherType(const FeatherType& type, float age) {
  age = std::clamp(age, 0.0f, 1.0f);
  if (age == 1) return type;
  const float shaft = ramp(age, 0, 0.3f);
  const float barbs = ramp(age, 0.3f, 0.5f);
  const float sheathFront = 1 - ramp(age, 0.5f, 0.8f);  // the migrating key barb's position
  const float rise = ramp(age, 0.8f, 1);
  // How far a barb at `position` has broken out: 0 in the sheath, 1 once the front is past it,
  // over a short edge (kSheathEdge of the vane) just below the front.
  auto opened = [&](float position) {
    if (sheathFront >= 1) return 0.0f;  // the sheath is whole
    return std::clamp((position - sheathFront) / kSheathEdge + 1, 0.0f, 1.0f);
  };

  FeatherType out = type;
  out.calamusLength *= shaft;
  out.rachisLength *= shaft;
  out.rachisWidth *= shaft;
  out.barbSpacingBase *= shaft;
  out.barbSpacingTip *= shaft;
  out.rachisSideCurvature *= rise;
  out.rachisFrontCurvature *= rise;

  out.keyBarbs.clear();
  for (BarbSide side : kSides) {
    const Vane& grown = type.vane(side);
    Vane& vane = out.vane(side);
    vane.barbLength *= barbs;
    for (SilhouettePoint& point : vane.silhouette) point.length *= barbs;
    // In the sheath the barbs lie along the rachis (180°) and open as the angles rise.
    vane.baseAngle = mix(180, grown.baseAngle, rise);
    vane.tipAngle = mix(180, grown.tipAngle, rise);

    // The extras first: a key barb of the feather at the same position comes later and wins
    // where the two tie (see VaneKeyBarbs).
    const std::vector<KeyBarb> keys = VaneKeyBarbs(type, side).keys();
    const KeyBarb atBase = grownBarbAtEnd(keys, 0);
    const KeyBarb atTip = grownBarbAtEnd(keys, 1);
    // A barb the sheath front has passed has broken out and stays open at its grown angle; below
    // the front it lies closed along the rachis (Sec. 4.2.4: the sheath opens from the tip).
    auto openAngle = [&](float position, float grownAngle) {
      return mix(180, grownAngle, opened(position));
    };
    out.keyBarbs.push_back(extraKeyBarb(side, 0, openAngle(0, vaneAngle(grown, 0)), atBase,
                                        vaneAngle(grown, 0), rise));
    out.keyBarbs.push_back(extraKeyBarb(side, 1, openAngle(1, vaneAngle(grown, 1)), atTip,
                                        vaneAngle(grown, 1), rise));
    out.keyBarbs.push_back(extraKeyBarb(side, sheathFront, vaneAngle(grown, sheathFront), atBase,
                                        vaneAngle(grown, 0), rise));
    // The edge of the sheath, just below the front: closed, so that the barbs below stay in it.
    const float inSheath = std::max(0.0f, sheathFront - kSheathEdge);
    out.keyBarbs.push_back(extraKeyBarb(side, inSheath, openAngle(inSheath, vaneAngle(grown, inSheath)),
                                        atBase, vaneAngle(grown, 0), rise));
    for (const KeyBarb& key : keys) {
      KeyBarb growing = key;
      growing.side = side;
      growing.vertices = mixVertices(straightened(key.vertices), key.vertices, rise);
      growing.plumulaceous = rise * key.plumulaceous;
      growing.angle = openAngle(key.position, key.angle.value_or(vaneAngle(grown, key.position)));
      out.keyBarbs.push_back(std::move(growing));
    }
  }
  if (type.afterfeather) {
    out.afterfeather =
        std::make_shared<const FeatherType>(grownFeatherType(*type.afterfeather, age));
  }
  return out;
}

}  // namespace hirsute
