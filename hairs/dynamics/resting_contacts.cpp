// Resting contacts kept from step to step and held at a resting distance (resting_contacts.h).
#include "hirsute/hairs/dynamics/resting_contacts.h"

#include <algorithm>
#include <cmath>

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// A contact's vertices merged by owner (a vane corner's share is its node's, as the impulses'
// of feather_coat_simulation.cpp), with the weight sum share^2 / mass of the gap's change.
struct Shares {
  std::array<int, 4> owners{};
  std::array<double, 4> shares{};
  int count = 0;
  double weight = 0;
};

Shares sharesOf(const RestingContact& c, const StepState& state) {
  Shares out;
  for (int k = 0; k < 4; ++k) {
    const int owner = state.owner[c.vertices[k]];
    int j = 0;
    while (j < out.count && out.owners[j] != owner) ++j;
    if (j == out.count) out.owners[out.count++] = owner;
    out.shares[j] += c.coefficients[k];
  }
  for (int j = 0; j < out.count; ++j)
    out.weight += out.shares[j] * out.shares[j] * state.inverseMass[out.owners[j]];
  return out;
}

double gapAlong(const RestingContact& c, const std::vector<Vector3d>& x) {
  double gap = 0;
  for (int k = 0; k < 4; ++k) gap += c.coefficients[k] * c.normal.dot(x[c.vertices[k]]);
  return gap;
}

// Applies `impulse` (mass times length) to the contact's owners along its normal.
void push(const RestingContact& c, const Shares& s, double impulse, StepState& state) {
  for (int j = 0; j < s.count; ++j)
    if (state.inverseMass[s.owners[j]] > 0)
      state.moveEnd(s.owners[j], impulse * s.shares[j] * state.inverseMass[s.owners[j]] * c.normal);
}

// The strain limit on the end positions (feather_stem.cpp's limitStrain, one mass-weighted
// pass): a segment outside the limit has its ends moved along it in proportion to their inverse
// masses, aiming a little inside.
bool limitSegment(const StrainSegment& segment, double limit, StepState& state) {
  const auto [i, j] = segment.vertices;
  const Vector3d along = state.end[j] - state.end[i];
  const double length = along.norm(), rest = segment.restLength;
  if (!(length > 0) || std::abs(length / rest - 1) <= limit) return false;
  const double aim = 0.999 * limit;
  const double target = std::clamp(length, rest * (1 - aim), rest * (1 + aim));
  const double wi = state.inverseMass[i], wj = state.inverseMass[j];
  if (!(wi + wj > 0)) return false;
  const Vector3d excess = (length - target) / length * along;
  state.moveEnd(i, wi / (wi + wj) * excess);
  state.moveEnd(j, -wj / (wi + wj) * excess);
  return true;
}

}  // namespace

void RestingContacts::update(std::vector<NearPair> near, const StepState& state,
                             const RestingOptions& options) {
  std::sort(near.begin(), near.end(),
            [](const NearPair& a, const NearPair& b) { return a.primitives < b.primitives; });
  std::vector<RestingContact> next;
  next.reserve(near.size());
  std::size_t old = 0;
  for (const NearPair& pair : near) {
    while (old < contacts_.size() && contacts_[old].primitives < pair.primitives) ++old;
    const RestingContact* held =
        old < contacts_.size() && contacts_[old].primitives == pair.primitives ? &contacts_[old]
                                                                               : nullptr;
    RestingContact c;
    c.primitives = pair.primitives;
    c.vertices = pair.vertices;
    c.coefficients = pair.coefficients;
    c.layerSign = pair.layerSign;
    Vector3d gap = Vector3d::Zero();
    double scale = 0;
    for (int k = 0; k < 4; ++k) {
      gap += pair.coefficients[k] * state.start[pair.vertices[k]];
      scale = std::max(scale, state.start[pair.vertices[k]].cwiseAbs().maxCoeff());
    }
    // An accepted state keeps the pair apart, so its gap names the side each primitive is on;
    // a gap lost in rounding keeps the side it was held on, or takes the layer order's.
    if (gap.norm() > 1e-12 * (1 + scale))
      c.normal = gap.normalized();
    else if (held != nullptr)
      c.normal = held->normal;
    else if (pair.layerSign != 0 && pair.layerNormal.norm() > 0)
      c.normal = pair.layerSign * pair.layerNormal.normalized();
    else
      continue;
    const double distance = c.normal.dot(gap);
    // A pair under the resting distance opens towards it at the repulsion's rate; one at or
    // beyond it comes no nearer than it.
    c.target = distance >= options.restDistance
                   ? options.restDistance
                   : std::min(options.restDistance,
                              distance + options.openingRate * (options.thickness - distance));
    if (held != nullptr) {
      c.multiplier = held->multiplier;
      c.steps = held->steps + 1;
    } else {
      c.steps = 1;
    }
    next.push_back(c);
  }
  contacts_ = std::move(next);
}

std::size_t RestingContacts::solve(StepState& state, const std::vector<StrainSegment>& segments,
                                   const RestingOptions& options) {
  std::vector<Shares> shares;
  shares.reserve(contacts_.size());
  for (const RestingContact& c : contacts_) shares.push_back(sharesOf(c, state));
  // The warm start: last step's impulse at once, which the sweeps take back where it is more
  // than this step needs (the multiplier never goes below zero: a contact only pushes).
  for (std::size_t k = 0; k < contacts_.size(); ++k)
    if (contacts_[k].multiplier > 0 && shares[k].weight > 0)
      push(contacts_[k], shares[k], contacts_[k].multiplier, state);
  std::size_t moved = 0;
  const auto sweep = [&] {
    for (std::size_t k = 0; k < contacts_.size(); ++k) {
      RestingContact& c = contacts_[k];
      if (!(shares[k].weight > 0)) continue;
      const double missing = c.target - gapAlong(c, state.end);
      const double next = std::max(0.0, c.multiplier + missing / shares[k].weight);
      const double change = next - c.multiplier;
      if (change == 0) continue;
      push(c, shares[k], change, state);
      c.multiplier = next;
      ++moved;
    }
  };
  for (int s = 0; s + 1 < options.sweeps; ++s) {
    sweep();
    for (const StrainSegment& segment : segments) limitSegment(segment, options.strainLimit, state);
  }
  sweep();
  return moved;
}

const RestingContact* RestingContacts::find(int first, int second) const {
  const std::array<int, 2> key{first, second};
  const auto it = std::lower_bound(
      contacts_.begin(), contacts_.end(), key,
      [](const RestingContact& c, const std::array<int, 2>& k) { return c.primitives < k; });
  return it != contacts_.end() && it->primitives == key ? &*it : nullptr;
}

}  // namespace hirsute::dynamics
