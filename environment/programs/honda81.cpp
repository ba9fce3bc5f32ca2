// honda81: collisions of tentacle tips (specification section 5.1). A query ?E(vigor[,group])
// is answered 0 when another query of its group, at least as vigorous, lies within the radius.
#include <algorithm>
#include <cmath>

#include "builtin_programs.h"

namespace hirsute::programs {
namespace {

class Honda81 : public BuiltinProgram {
 public:
  Honda81(const CommunicationFile& file, const ProgramCommand& command, Diagnostics& diagnostics)
      : BuiltinProgram("honda81", file, diagnostics) {
    for (const KeywordLine& line : readSpecification(command, file)) {
      const std::vector<KeywordToken> values = line.tokens("x,; \t:\n");
      if (line.keyword == "verbose") {
        // Diagnostics of the original on stderr; accepted, nothing to print here.
      } else if (line.keyword == "radius") {
        if (!values.empty()) {
          const float rho = keywordNumber(line, values[0]);
          radiusSquared_ = rho * rho;
        }
      } else if (line.keyword == "3d case") {
        threeD_ = !values.empty() && values[0].text == "on";
      } else {
        warnUnknownKeyword(line, diagnostics, "honda81");
      }
    }
  }

 protected:
  void answer(const std::vector<EnvironmentQueryRecord>& batch, std::string& answers) override {
    struct Tip {
      unsigned long id;
      float x, y, z, vigor;
      int group;
    };
    std::vector<Tip> tips;
    for (const EnvironmentQueryRecord& q : batch) {
      if (q.counts[kPosition] < 3 || q.module.values.empty()) {
        reject("honda81 needs ?E(vigor[,group]) and the turtle position (three values)");
        continue;
      }
      const auto& p = q.turtle[kPosition];
      tips.push_back(Tip{q.id, p[0], threeD_ ? p[1] : p[2], threeD_ ? p[2] : 0.0f,
                         q.module.value(0),
                         q.module.values.size() > 1 ? static_cast<int>(q.module.value(1)) : 0});
    }
    // The pairwise test of the original over every pair, with the pairs sought among the tips
    // sorted by x: two tips further apart in x than the radius (with a margin for rounding)
    // cannot be within it.
    // A tip at x = NaN is within no radius: it blocks nothing and nothing blocks it.
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < tips.size(); ++i) {
      if (!std::isnan(tips[i].x)) order.push_back(i);
    }
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return tips[a].x < tips[b].x; });
    const double reach = std::sqrt(static_cast<double>(radiusSquared_)) * 1.001 + 1e-30;
    std::vector<bool> blocked(tips.size(), false);
    for (std::size_t a = 0; a < order.size(); ++a) {
      const Tip& i = tips[order[a]];
      for (std::size_t b = a + 1; b < order.size(); ++b) {
        const Tip& j = tips[order[b]];
        if (static_cast<double>(j.x) - static_cast<double>(i.x) > reach) break;
        if (i.group != j.group || !within(i, j)) continue;
        if (i.vigor <= j.vigor) blocked[order[a]] = true;
        if (j.vigor <= i.vigor) blocked[order[b]] = true;
      }
    }
    for (std::size_t i = 0; i < tips.size(); ++i) {
      appendAnswerRecord(answers, tips[i].id, {blocked[i] ? 0.0f : 1.0f});
    }
  }

 private:
  template <typename Tip>
  bool within(const Tip& i, const Tip& j) const {
    const float dx = i.x - j.x, dy = i.y - j.y, dz = i.z - j.z;
    // 3-D: (dx² + dy²) + dz²; 2-D: dx² + dz² over the turtle's x and z (kept in x and y here).
    const float d = threeD_ ? dx * dx + dy * dy + dz * dz : dx * dx + dy * dy;
    return d <= radiusSquared_;
  }

  float radiusSquared_ = 0;
  bool threeD_ = false;
};

}  // namespace

std::unique_ptr<EnvironmentProgram> makeHonda81(const CommunicationFile& file,
                                                const ProgramCommand& command,
                                                Diagnostics& diagnostics) {
  return std::make_unique<Honda81>(file, command, diagnostics);
}

}  // namespace hirsute::programs
