// density: a 2-D field of the queries around each other (specification section 5.6, which
// only summarises the original). ?E(v) is a source of strength v at the turtle's (x, y);
// ?E(a,b,c) asks for the field at the turtle; other queries only count in the field. The field
// at p is the sum over the other queries q of 1/(1 + |p−q|²) plus the sum over the sources s of
// v_s/(1 + |p−s|). The answer: the least field value on a 6×6 grid of samples over a square of
// side 1 centred at p (or the value at p, `one point value: on`), and the gradient at p as its
// direction in degrees (0 to 360) and its length, or as the vector (`return vector: yes`).
// Where the summary leaves the method open (the sample square, an analytic gradient), this
// is Hirsute's reading, documented in docs/environment.md.
#include <algorithm>
#include <cmath>

#include "builtin_programs.h"

namespace hirsute::programs {
namespace {

class Density : public BuiltinProgram {
 public:
  Density(const CommunicationFile& file, const ProgramCommand& command, Diagnostics& diagnostics)
      : BuiltinProgram("density", file, diagnostics) {
    for (const KeywordLine& line : readSpecification(command, file)) {
      const std::vector<KeywordToken> values = line.tokens("x,; \t:\n");
      const std::string first = values.empty() ? std::string() : values[0].text;
      if (line.keyword == "one point value") {
        onePoint_ = first == "on" || first == "yes";
      } else if (line.keyword == "return vector") {
        returnVector_ = first == "on" || first == "yes";
      } else if (line.keyword == "verbose") {
      } else if (line.keyword == "range" || line.keyword == "position" ||
                 line.keyword == "frame intervals" || line.keyword == "quantization step" ||
                 line.keyword == "gamma") {
        for (const KeywordToken& t : values)
          keywordNumber(line, t);  // checked; they only shape the image
      } else if (line.keyword == "output image") {
        diagnostics.warn(line.at(1),
                         "density: the field is not written as an image; the line is ignored");
      } else {
        warnUnknownKeyword(line, diagnostics, "density");
      }
    }
  }

 protected:
  void answer(const std::vector<EnvironmentQueryRecord>& batch, std::string& answers) override {
    struct Point {
      unsigned long id;
      double x, y, strength;
      bool source, asks;
    };
    std::vector<Point> points;
    for (const EnvironmentQueryRecord& q : batch) {
      if (q.counts[kPosition] < 2) {
        reject("density needs the turtle position (two values at least)");
        continue;
      }
      const std::size_t n = q.module.values.size();
      points.push_back(Point{q.id, q.turtle[kPosition][0], q.turtle[kPosition][1],
                             q.module.value(0), n == 1, n == 3});
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!points[i].asks) continue;
      const Point& p = points[i];
      const auto field = [&](double x, double y) {
        double f = 0;
        for (std::size_t j = 0; j < points.size(); ++j) {
          if (j == i) continue;
          const double dx = x - points[j].x, dy = y - points[j].y, d2 = dx * dx + dy * dy;
          f += points[j].source ? points[j].strength / (1 + std::sqrt(d2)) : 1 / (1 + d2);
        }
        return f;
      };
      double value = field(p.x, p.y);
      if (!onePoint_) {
        for (int a = 0; a < 6; ++a)
          for (int b = 0; b < 6; ++b)
            value = std::min(value, field(p.x + a / 5.0 - 0.5, p.y + b / 5.0 - 0.5));
      }
      double gx = 0, gy = 0;
      for (std::size_t j = 0; j < points.size(); ++j) {
        if (j == i) continue;
        const double dx = p.x - points[j].x, dy = p.y - points[j].y, d2 = dx * dx + dy * dy;
        double k;
        if (points[j].source) {
          const double d = std::sqrt(d2);
          k = d > 0 ? -points[j].strength / (d * (1 + d) * (1 + d)) : 0;
        } else {
          k = -2 / ((1 + d2) * (1 + d2));
        }
        gx += k * dx;
        gy += k * dy;
      }
      if (returnVector_) {
        appendAnswerRecord(
            answers, p.id,
            {static_cast<float>(value), static_cast<float>(gx), static_cast<float>(gy)});
      } else {
        double angle = std::atan2(gy, gx) * 180 / M_PI;
        if (angle < 0) angle += 360;
        appendAnswerRecord(answers, p.id,
                           {static_cast<float>(value), static_cast<float>(angle),
                            static_cast<float>(std::hypot(gx, gy))});
      }
    }
  }

 private:
  bool onePoint_ = false;
  bool returnVector_ = false;
};

}  // namespace

std::unique_ptr<EnvironmentProgram> makeDensity(const CommunicationFile& file,
                                                const ProgramCommand& command,
                                                Diagnostics& diagnostics) {
  return std::make_unique<Density>(file, command, diagnostics);
}

}  // namespace hirsute::programs
