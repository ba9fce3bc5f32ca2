// chiba: the light that reaches leaf clusters, balls in a voxel grid (Chiba et al. 1994;
// specification section 5.3). ?E(r) or ?E(r,a,b,c…) is answered with the light S reaching the
// ball of radius r at the turtle (and, with four or more parameters, the normalised direction
// the light comes from), summed over the light sources or a sphere of sample directions. Rays
// step through the grid as the original steps them, defect included (its face tracker is
// measured from the grid's origin but compared with world coordinates), so that the answers
// are the original's to the bit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <list>

#include "builtin_programs.h"

namespace hirsute::programs {
namespace {

constexpr long kMaxCells = 16'000'000;
constexpr int kMaxSources = 100;
constexpr int kMaxLevel = 8;  // 8·4^7 = 131072 sample directions

using Vec = std::array<float, 3>;

// ℓ = sqrt of the f32 squared length, in f64; each component divided by it in f32.
Vec normalise(Vec v) {
  const float squared = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const float length = static_cast<float>(std::sqrt(static_cast<double>(squared)));
  if (length > 0) {
    for (float& c : v) c = c / length;
  }
  return v;
}

struct Source {
  Vec direction;
  float weight;
};

using Point = std::array<double, 3>;

Point unit(const Point& p) {
  const double s = 1 / std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return {p[0] * s, p[1] * s, p[2] * s};
}

Point mid(const Point& u, const Point& v) {
  return {(u[0] + v[0]) * 0.5, (u[1] + v[1]) * 0.5, (u[2] + v[2]) * 0.5};
}

class Chiba : public BuiltinProgram {
 public:
  Chiba(const CommunicationFile& file, const ProgramCommand& command, Diagnostics& diagnostics)
      : BuiltinProgram("chiba", file, diagnostics) {
    const char* withX = "x,; \t:\n";
    const char* withoutX = ",; \t:\n";
    int samples = 20;
    bool estimateArea = false, cie = false;
    std::vector<Source> sources;
    for (const KeywordLine& line : readSpecification(command, file)) {
      const std::vector<KeywordToken> a = line.tokens(withX);
      const std::vector<KeywordToken> b = line.tokens(withoutX);
      const std::string first = a.empty() ? std::string() : a[0].text;
      const auto number = [&](float& into) {
        if (!b.empty()) into = keywordNumber(line, b[0]);
      };
      if (line.keyword == "grid size") {
        for (std::size_t c = 0; c < 3 && c < a.size(); ++c) {
          cells_[c] = keywordInteger(line, a[c]);
          if (cells_[c] < 1)
            throw DiagnosticError(line.at(a[c].column), "the grid needs at least one cell");
        }
        if (static_cast<long>(cells_[0]) * cells_[1] * cells_[2] > kMaxCells) {
          throw DiagnosticError(line.at(a[0].column),
                                "the grid has more than " + std::to_string(kMaxCells) + " cells");
        }
      } else if (line.keyword == "verbose") {
      } else if (line.keyword == "lower to upper ratio") {
        number(ratio_);
      } else if (line.keyword == "transmittance") {
        number(transmittance_);
      } else if (line.keyword == "number of samples") {
        if (!a.empty()) samples = keywordInteger(line, a[0]);
      } else if (line.keyword == "radius") {
        number(radius_);
      } else if (line.keyword == "beam radius") {
        number(beam_);
      } else if (line.keyword == "source direction") {
        // Three components split without `x`, then the intensity from the rest with it; a line
        // with fewer than four values adds no source.
        if (b.size() < 3) continue;
        Source s{};
        for (int c = 0; c < 3; ++c) s.direction[c] = keywordNumber(line, b[c]);
        KeywordLine tail = line;
        tail.rest = static_cast<std::size_t>(b[2].column - 1) + b[2].text.size();
        const std::vector<KeywordToken> w = tail.tokens(withX);
        if (w.empty()) continue;
        s.weight = keywordNumber(line, w[0]);
        if (static_cast<int>(sources.size()) == kMaxSources) {
          throw DiagnosticError(line.at(1),
                                "more than " + std::to_string(kMaxSources) + " light sources");
        }
        sources.push_back(s);
      } else if (line.keyword == "estimate intersection area") {
        estimateArea = first == "on";
      } else if (line.keyword == "use CIE formula") {
        cie = first == "yes";
      } else {
        warnUnknownKeyword(line, diagnostics, "chiba");
      }
    }
    if (!sources.empty()) {
      float sum = 0;
      for (const Source& s : sources) sum = sum + s.weight;
      for (Source& s : sources) {
        s.weight = s.weight / sum;
        s.direction = normalise(s.direction);
      }
      sources_ = std::move(sources);
    } else {
      sampleSphere(samples, cie, command);
    }
    estimateArea_ = estimateArea;
    if (estimateArea_) beam_ = 1;
  }

 protected:
  void answer(const std::vector<EnvironmentQueryRecord>& batch, std::string& answers) override {
    balls_.clear();
    for (const EnvironmentQueryRecord& q : batch) {
      const std::size_t n = q.module.values.size();
      if ((n != 1 && n < 4) || q.counts[kPosition] < 3) {
        reject("chiba needs ?E(r) or ?E(r,a,b,c…) and the turtle position (three values)");
        continue;
      }
      Ball ball;
      ball.id = q.id;
      ball.centre = q.turtle[kPosition];
      const float r0 = q.module.value(0);
      ball.r = r0 > 0 ? r0 : radius_;
      ball.area = static_cast<float>(M_PI * ball.r * ball.r);
      ball.parameters = n;
      balls_.push_back(ball);
    }
    if (balls_.empty()) return;
    buildGrid();
    counter_ = 0;
    for (std::size_t i = 0; i < balls_.size(); ++i) {
      float sum = 0;
      Vec towards{0, 0, 0};
      for (const Source& s : sources_) {
        const float light = ray(i, s);
        sum = sum + light;
        for (int c = 0; c < 3; ++c) towards[c] = towards[c] + light * s.direction[c];
      }
      std::vector<std::optional<float>> values(balls_[i].parameters);
      values[0] = sum;
      if (balls_[i].parameters >= 4) {
        const Vec d = normalise(towards);
        for (int c = 0; c < 3; ++c) values[1 + c] = d[c];
      }
      appendAnswerRecord(answers, balls_[i].id, values);
    }
  }

 private:
  struct Ball {
    unsigned long id = 0;
    Vec centre{};
    float r = 0, area = 0;
    std::size_t parameters = 0;
    std::uint32_t mark = 0;
  };

  void sampleSphere(int samples, bool cie, const ProgramCommand& command) {
    // level = ceil(log(n/8)/log 4) + 1, at least 1 (the octahedron).
    int level = 1;
    if (samples > 8) {
      const double l = std::ceil(std::log(samples / 8.0) / std::log(4.0)) + 1;
      level = l > kMaxLevel ? kMaxLevel + 1 : static_cast<int>(l);
    }
    if (level > kMaxLevel) {
      throw DiagnosticError(command.specificationWhere,
                            "chiba: the number of samples asks for more than 131072 directions");
    }
    const Point xp{1, 0, 0}, xm{-1, 0, 0}, yp{0, 1, 0}, ym{0, -1, 0}, zp{0, 0, 1}, zm{0, 0, -1};
    using Face = std::array<Point, 3>;
    std::vector<Face> faces = {{xp, zp, yp}, {yp, zp, xm}, {xm, zp, ym}, {ym, zp, xp},
                               {xp, yp, zm}, {yp, xm, zm}, {xm, ym, zm}, {ym, xp, zm}};
    for (Face& f : faces) std::swap(f[0], f[2]);
    for (int l = 1; l < level; ++l) {
      std::vector<Face> finer;
      finer.reserve(faces.size() * 4);
      for (const Face& f : faces) {
        const Point a = unit(mid(f[0], f[2])), b = unit(mid(f[0], f[1])), c = unit(mid(f[1], f[2]));
        finer.push_back({f[0], b, a});
        finer.push_back({b, f[1], c});
        finer.push_back({a, b, c});
        finer.push_back({a, c, f[2]});
      }
      faces = std::move(finer);
    }
    const int n = static_cast<int>(faces.size());
    int upper = 0;
    for (const Face& f : faces) {
      Vec d;
      for (int c = 0; c < 3; ++c) {
        const float sum =
            static_cast<float>(f[0][c]) + static_cast<float>(f[1][c]) + static_cast<float>(f[2][c]);
        d[c] = static_cast<float>(sum / 3.0);
      }
      d = normalise(d);
      if (d[1] >= 0) ++upper;
      sources_.push_back(Source{d, 0});
    }
    const float onePlus = 1 + ratio_;
    if (!cie) {
      for (Source& s : sources_) {
        s.weight =
            s.direction[1] >= 0 ? static_cast<float>(1.0 / upper / static_cast<double>(onePlus))
            : n == upper
                ? 0.0f
                : static_cast<float>(static_cast<double>(ratio_ / static_cast<float>(n - upper)) /
                                     static_cast<double>(onePlus));
      }
      return;
    }
    float sum = 0;
    for (Source& s : sources_) {
      const Vec& d = s.direction;
      if (d[1] <= 0) {
        s.weight = 0;
      } else {
        const double c =
            d[1] / std::sqrt(static_cast<double>(d[0]) * d[0] + static_cast<double>(d[1]) * d[1]);
        s.weight = static_cast<float>((1 + c) / 3 * (8.6 * c + 0.123) / 0.203);
      }
      sum = sum + s.weight;
    }
    if (sum > 0) {
      for (Source& s : sources_) s.weight = s.weight / sum;
    }
  }

  void buildGrid() {
    const Ball& first = balls_.front();
    for (int c = 0; c < 3; ++c) {
      origin_[c] = first.centre[c] - first.r;
      extent_[c] = 2 * first.r;
    }
    maxRadius_ = first.r;
    for (std::size_t i = 1; i < balls_.size(); ++i) {
      const Ball& b = balls_[i];
      for (int c = 0; c < 3; ++c) {
        float e = origin_[c] - (b.centre[c] - b.r);
        if (e > 0) {
          origin_[c] = origin_[c] - e;
          extent_[c] = extent_[c] + e;
        }
        e = (b.centre[c] + b.r) - (origin_[c] + extent_[c]);
        if (e > 0) extent_[c] = extent_[c] + e;
      }
      maxRadius_ = std::max(maxRadius_, b.r);
    }
    cellLists_.assign(static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2], {});
    float squares = 0;
    for (int c = 0; c < 3; ++c) {
      const float h = extent_[c] / static_cast<float>(cells_[c]);
      squares = squares + h * h;
    }
    const float half = static_cast<float>(0.5 * std::sqrt(static_cast<double>(squares)));
    const float reach = maxRadius_ * beam_;
    for (std::size_t i = 0; i < balls_.size(); ++i) {
      const Ball& b = balls_[i];
      int lo[3], hi[3];
      for (int c = 0; c < 3; ++c) {
        const float n = static_cast<float>(cells_[c]);
        lo[c] =
            std::max(0, floorIndex((b.centre[c] - b.r - reach - origin_[c]) / extent_[c] * n) - 1);
        hi[c] = std::min(cells_[c] - 1,
                         1 + floorIndex((b.centre[c] + b.r + reach - origin_[c]) / extent_[c] * n));
      }
      const float R = b.r + reach + half;
      const float R2 = R * R;
      for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
          for (int x = lo[0]; x <= hi[0]; ++x) {
            const int index[3] = {x, y, z};
            float e[3];
            for (int c = 0; c < 3; ++c) {
              const float m = static_cast<float>(
                  origin_[c] + (static_cast<double>(static_cast<float>(index[c])) + 0.5) /
                                   cells_[c] * extent_[c]);
              e[c] = b.centre[c] - m;
            }
            if (e[0] * e[0] + e[1] * e[1] + e[2] * e[2] <= R2)
              cellLists_[cellIndex(x, y, z)].push_front(i);
          }
    }
  }

  std::size_t cellIndex(int x, int y, int z) const {
    return (static_cast<std::size_t>(z) * cells_[1] + y) * cells_[0] + x;
  }

  // Light of source `s` reaching ball i, stepping cell by cell towards the source.
  float ray(std::size_t i, const Source& s) {
    if (s.weight == 0) return 0;
    if (++counter_ == 0) {
      counter_ = 1;
      for (Ball& b : balls_) b.mark = 0;
    }
    Ball& self = balls_[i];
    self.mark = counter_;
    const Vec& d = s.direction;
    const Vec& p = self.centre;
    float rho = 1;
    float eta[3], mu[3];
    int step[3], k[3], cell[3];
    for (int c = 0; c < 3; ++c) {
      eta[c] = static_cast<float>(0.5 * extent_[c] / cells_[c]);
      if (d[c] < 0) eta[c] = -eta[c];
      step[c] = d[c] < 0 ? -1 : 1;
      k[c] = floorIndex((p[c] - origin_[c]) / extent_[c] * static_cast<float>(cells_[c]));
      mu[c] = static_cast<float>((k[c] + 0.5) / cells_[c] * extent_[c]);
      cell[c] = std::clamp(k[c], 0, cells_[c] - 1);
    }
    const long limit = 4L * (cells_[0] + cells_[1] + cells_[2]) + 16;
    for (long steps = 0; steps < limit; ++steps) {
      for (std::size_t j : cellLists_[cellIndex(cell[0], cell[1], cell[2])]) {
        Ball& other = balls_[j];
        if (other.mark == counter_) continue;
        const float blocked = blocking(self, other, d);
        if (!(blocked > 0)) continue;
        other.mark = counter_;
        if (estimateArea_) {
          rho = rho * (1 - (1 - transmittance_) * blocked / self.area);
        } else {
          rho = static_cast<float>(rho * std::pow(static_cast<double>(transmittance_),
                                                  blocked / (2.0 * (other.r + beam_ * self.r))));
        }
      }
      int axis = 0;
      float value = std::fabs(mu[0] + eta[0] - p[0]);
      for (int c = 1; c < 3; ++c) {
        const float t = mu[c] + eta[c] - p[c];
        if (std::fabs(t * d[axis]) < std::fabs(value * d[c])) {
          axis = c;
          value = t;
        }
      }
      mu[axis] = mu[axis] + 2 * eta[axis];
      cell[axis] += step[axis];
      k[axis] += d[axis] > 0 ? 1 : -1;
      if (k[axis] < 0 || k[axis] >= cells_[axis]) return s.weight * rho;
      // The original's edge case (an axis with d = 0 chosen) can walk the cell off the grid,
      // where it has no list; the ray ends there.
      if (cell[axis] < 0 || cell[axis] >= cells_[axis]) return s.weight * rho;
    }
    return s.weight * rho;
  }

  // How much ball `o` blocks the ray from ball `b` towards d: the area it covers of b's disc,
  // or the chord the ray cuts through it.
  float blocking(const Ball& b, const Ball& o, const Vec& d) const {
    float v[3];
    for (int c = 0; c < 3; ++c) v[c] = b.centre[c] - o.centre[c];
    const float alpha = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
    const float vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (estimateArea_) {
      if (alpha > 0) return 0;
      const float q = vv - alpha * alpha;
      const float sumR = o.r + b.r;
      if (q >= sumR * sumR) return 0;
      const float delta = static_cast<float>(std::sqrt(static_cast<double>(q)));
      const float R1 = o.r < b.r ? b.r : o.r;
      const float R2 = o.r < b.r ? o.r : b.r;
      const float R1s = R1 * R1, R2s = R2 * R2;
      if (delta + R2 <= R1) return static_cast<float>(M_PI * R2s);
      const float x1 = (R1s + delta * delta - R2s) / (2 * delta);
      const float x2 = (R2s + delta * delta - R1s) / (2 * delta);
      const float y = static_cast<float>(std::sqrt(static_cast<double>(R2s - x2 * x2)));
      return static_cast<float>(R1s * std::acos(static_cast<double>(x1 / R1)) +
                                R2s * std::acos(static_cast<double>(x2 / R2)) -
                                static_cast<double>(y * delta));
    }
    const float rr = o.r + b.r * beam_;
    const float D = alpha * alpha - vv + rr * rr;
    if (!(D >= 0)) return 0;
    const float s = static_cast<float>(std::sqrt(static_cast<double>(D)));
    if (!(-alpha + s > 0)) return 0;
    return -alpha - s >= 0 ? 2 * s : -alpha + s;
  }

  std::array<int, 3> cells_{1, 1, 1};
  float ratio_ = 0.7f, transmittance_ = 0.6f, radius_ = 25, beam_ = 0;
  bool estimateArea_ = false;
  std::vector<Source> sources_;
  std::vector<Ball> balls_;
  std::array<float, 3> origin_{}, extent_{};
  float maxRadius_ = 0;
  std::vector<std::list<std::size_t>> cellLists_;
  std::uint32_t counter_ = 0;
};

}  // namespace

std::unique_ptr<EnvironmentProgram> makeChiba(const CommunicationFile& file,
                                              const ProgramCommand& command,
                                              Diagnostics& diagnostics) {
  return std::make_unique<Chiba>(file, command, diagnostics);
}

}  // namespace hirsute::programs
