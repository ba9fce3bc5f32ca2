// ecosystem: competition of circles (specification section 5.2). ?E(radius[,group]) is
// answered 0 when its circle meets the circle of a plant at least as large in its group.
#include <algorithm>
#include <cmath>

#include "builtin_programs.h"

namespace hirsute::programs {
namespace {

constexpr long kMaxCells = 16'000'000;

class Ecosystem : public BuiltinProgram {
 public:
  Ecosystem(const CommunicationFile& file, const ProgramCommand& command, Diagnostics& diagnostics)
      : BuiltinProgram("ecosystem", file, diagnostics) {
    for (const KeywordLine& line : readSpecification(command, file)) {
      const std::vector<KeywordToken> values = line.tokens("x,; \t:\n");
      const std::string first = values.empty() ? std::string() : values[0].text;
      if (line.keyword == "verbose") {
      } else if (line.keyword == "grid size") {
        for (std::size_t c = 0; c < 3 && c < values.size(); ++c) {
          cells_[c] = std::max(1, keywordInteger(line, values[c]));
        }
        if (static_cast<long>(cells_[0]) * cells_[1] * cells_[2] > kMaxCells) {
          throw DiagnosticError(line.at(values[0].column),
                                "the grid has more than " + std::to_string(kMaxCells) + " cells");
        }
      } else if (line.keyword == "3d case") {
        threeD_ = first == "on" || first == "yes";
      } else if (line.keyword == "vigor") {
        vigorMode_ = first == "on";
      } else {
        warnUnknownKeyword(line, diagnostics, "ecosystem");
      }
    }
  }

 protected:
  void answer(const std::vector<EnvironmentQueryRecord>& batch, std::string& answers) override {
    struct Plant {
      unsigned long id;
      std::array<float, 3> q;
      float r, vigor;
      int group;
      std::array<int, 3> lo, hi;
    };
    std::vector<Plant> plants;
    const int axes = threeD_ ? 3 : 2;
    std::array<float, 3> low{}, high{};
    for (const EnvironmentQueryRecord& e : batch) {
      if (e.counts[kPosition] < 3 || e.module.values.size() < (vigorMode_ ? 2u : 1u)) {
        reject(vigorMode_
                   ? "ecosystem needs ?E(radius,vigor) and the turtle position (three values)"
                   : "ecosystem needs ?E(radius[,group]) and the turtle position (three values)");
        continue;
      }
      const auto& t = e.turtle[kPosition];
      Plant p{};
      p.id = e.id;
      p.q = threeD_ ? t : std::array<float, 3>{t[0], t[2], 0.0f};
      p.r = e.module.value(0);
      if (vigorMode_) {
        p.vigor = e.module.value(1, 1.0f);
        p.group = 0;
      } else {
        p.vigor = 1;
        p.group = e.module.values.size() > 1 ? static_cast<int>(e.module.value(1)) : 0;
      }
      // The box: the first query uses the raw turtle triple (its y in 2-D, as the original
      // does), the later ones their stored point.
      for (int c = 0; c < axes; ++c) {
        if (plants.empty()) {
          low[c] = t[c] - p.r;
          high[c] = t[c] + p.r;
        } else {
          low[c] = std::min(low[c], p.q[c] - p.r);
          high[c] = std::max(high[c], p.q[c] + p.r);
        }
      }
      plants.push_back(p);
    }
    if (plants.empty()) return;

    std::array<float, 3> origin{}, extent{};
    for (int c = 0; c < axes; ++c) {
      origin[c] = static_cast<float>(static_cast<double>(low[c]) - 0.001);
      extent[c] = static_cast<float>(static_cast<double>(high[c] - low[c]) + 0.002);
    }
    const std::array<int, 3> n{cells_[0], cells_[1], threeD_ ? cells_[2] : 1};
    std::vector<std::vector<std::size_t>> grid(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
    const auto cell = [&](int x, int y, int z) -> std::vector<std::size_t>& {
      return grid[(static_cast<std::size_t>(z) * n[1] + y) * n[0] + x];
    };
    for (std::size_t i = 0; i < plants.size(); ++i) {
      Plant& p = plants[i];
      for (int c = 0; c < 3; ++c) {
        if (c >= axes) {
          p.lo[c] = p.hi[c] = 0;
          continue;
        }
        const float nc = static_cast<float>(n[c]);
        const float a = (p.q[c] - p.r - origin[c]) / extent[c] * nc;
        const float b = (p.q[c] + p.r - origin[c]) / extent[c] * nc;
        p.lo[c] = std::max(0, floorIndex(a) - 1);
        p.hi[c] = std::min(n[c] - 1, 1 + floorIndex(b));
      }
      for (int z = p.lo[2]; z <= p.hi[2]; ++z)
        for (int y = p.lo[1]; y <= p.hi[1]; ++y)
          for (int x = p.lo[0]; x <= p.hi[0]; ++x) cell(x, y, z).push_back(i);
    }
    std::vector<bool> removed(plants.size(), false);
    for (std::size_t a = 0; a < plants.size(); ++a) {
      const Plant& pa = plants[a];
      bool dominated = false;
      for (int z = pa.lo[2]; z <= pa.hi[2] && !dominated; ++z)
        for (int y = pa.lo[1]; y <= pa.hi[1] && !dominated; ++y)
          for (int x = pa.lo[0]; x <= pa.hi[0] && !dominated; ++x)
            for (std::size_t b : cell(x, y, z)) {
              if (b == a) continue;
              const Plant& pb = plants[b];
              if (pb.group != pa.group || !meet(pa, pb, axes)) continue;
              if (vigorMode_) {
                if (removed[b]) continue;
                if (pa.vigor < pb.vigor || (pa.vigor == pb.vigor && pa.r < pb.r)) dominated = true;
              } else if (pa.r <= pb.r) {
                dominated = true;
              }
              if (dominated) break;
            }
      if (dominated && vigorMode_) removed[a] = true;
      appendAnswerRecord(answers, pa.id, {dominated ? 0.0f : 1.0f});
    }
  }

 private:
  template <typename Plant>
  static bool meet(const Plant& a, const Plant& b, int axes) {
    const float dx = a.q[0] - b.q[0], dy = a.q[1] - b.q[1];
    const float dz = axes == 3 ? a.q[2] - b.q[2] : 0.0f;
    const float d = dx * dx + dy * dy + dz * dz;
    const float reach = a.r + b.r;
    return d <= reach * reach;
  }

  std::array<int, 3> cells_{1, 1, 1};
  bool threeD_ = false;
  bool vigorMode_ = false;
};

}  // namespace

std::unique_ptr<EnvironmentProgram> makeEcosystem(const CommunicationFile& file,
                                                  const ProgramCommand& command,
                                                  Diagnostics& diagnostics) {
  return std::make_unique<Ecosystem>(file, command, diagnostics);
}

}  // namespace hirsute::programs
