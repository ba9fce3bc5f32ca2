// clover: light on the ground from an image, shaded by the leaves above it (specification
// section 5.4). ?E(0 or one parameter) asks for the light at the turtle; ?E(1,area) adds a
// leaf's disc to the grid of leaf counts and ?E(2,area) removes it. The counts persist from
// one batch to the next.
#include <cmath>

#include "builtin_programs.h"
#include "hirsute/core/model_folder.h"
#include "hirsute/interpreter/texture_image.h"

namespace hirsute::programs {
namespace {

constexpr long kMaxCells = 64'000'000;

class Clover : public BuiltinProgram {
 public:
  Clover(const CommunicationFile& file, const ProgramCommand& command, Diagnostics& diagnostics)
      : BuiltinProgram("clover", file, diagnostics) {
    std::optional<Texture> image;
    for (const KeywordLine& line : readSpecification(command, file)) {
      const std::vector<KeywordToken> grid = line.tokens("x,; \t:\n");
      const std::vector<KeywordToken> values = line.tokens(",; \t:\n");
      const std::string first = values.empty() ? std::string() : values[0].text;
      if (line.keyword == "grid size") {
        for (std::size_t c = 0; c < 2 && c < grid.size(); ++c) {
          size_[c] = keywordInteger(line, grid[c]);
          if (size_[c] < 1)
            throw DiagnosticError(line.at(grid[c].column), "the grid needs at least one cell");
        }
        if (static_cast<long>(size_[0]) * size_[1] > kMaxCells) {
          throw DiagnosticError(line.at(grid[0].column),
                                "the grid has more than " + std::to_string(kMaxCells) + " cells");
        }
      } else if (line.keyword == "grid position") {
        for (std::size_t c = 0; c < 2 && c < grid.size(); ++c)
          corner_[c] = keywordNumber(line, grid[c]);
      } else if (line.keyword == "grid range") {
        for (std::size_t c = 0; c < 2 && c < grid.size(); ++c)
          range_[c] = keywordNumber(line, grid[c]);
      } else if (line.keyword == "verbose") {
      } else if (line.keyword == "transmittance") {
        if (!values.empty()) transmittance_ = keywordNumber(line, values[0]);
        if (transmittance_ == 0) transmittance_ = 0.0001f;
      } else if (line.keyword == "input image") {
        if (values.empty())
          throw DiagnosticError(line.at(static_cast<int>(line.rest) + 1), "expected an image file");
        // The image is read beside the specification and must stay beneath its folder.
        const ModelFolder folder(file.file.parent_path());
        const std::string refused = folder.refusal(first);
        if (!refused.empty()) {
          throw DiagnosticError(line.at(values[0].column),
                                "cannot open '" + first + "': " + refused);
        }
        const std::filesystem::path name = folder.pathOf(first);
        try {
          image = loadTexture(name);
        } catch (const DiagnosticError& e) {
          throw DiagnosticError(line.at(values[0].column),
                                e.diagnostic().message + " (" + name.string() + ")");
        }
      } else if (line.keyword == "remove old leaves") {
        removeOldLeaves_ = first == "on" || first == "yes";
      } else if (line.keyword == "z is up") {
        zIsUp_ = !(first == "no" || first == "off");
      } else {
        warnUnknownKeyword(line, diagnostics, "clover");
      }
    }
    const std::size_t cells =
        static_cast<std::size_t>(size_[0]) * static_cast<std::size_t>(size_[1]);
    light_.assign(cells, 255);
    ratio_.assign(cells, 255);
    leaves_.assign(cells, 0);
    if (image) sample(*image);
    powers_[0] = 1;
    for (std::size_t m = 1; m < powers_.size(); ++m) powers_[m] = transmittance_ * powers_[m - 1];
  }

 protected:
  void answer(const std::vector<EnvironmentQueryRecord>& batch, std::string& answers) override {
    if (removeOldLeaves_) std::fill(leaves_.begin(), leaves_.end(), 0);
    struct LightQuery {
      unsigned long id;
      float x, y;
      std::size_t parameters;
    };
    std::vector<LightQuery> light;
    for (const EnvironmentQueryRecord& q : batch) {
      if (q.counts[kPosition] < (zIsUp_ ? 2 : 3) || q.module.values.empty()) {
        reject("clover needs ?E with a parameter and the turtle position");
        continue;
      }
      const auto& t = q.turtle[kPosition];
      const float x = t[0], y = zIsUp_ ? t[1] : t[2];
      const float kind = q.module.value(0);
      if (q.module.values.size() == 1 || kind == 0) {
        light.push_back(LightQuery{q.id, x, y, q.module.values.size()});
      } else {
        stampLeaf(x, y, q.module.value(1), kind == 1);
      }
    }
    for (const LightQuery& q : light) {
      const int i = floorIndex((q.x - corner_[0]) / range_[0] * static_cast<float>(size_[0]));
      const int j = floorIndex((q.y - corner_[1]) / range_[1] * static_cast<float>(size_[1]));
      float value = 0, ratio = 0;
      if (i >= 0 && i < size_[0] && j >= 0 && j < size_[1]) {
        const std::size_t c = cell(i, j);
        value = static_cast<float>(light_[c] / 255.0 * static_cast<double>(powers_[leaves_[c]]));
        ratio = static_cast<float>(ratio_[c] / 128.0);
      }
      if (q.parameters >= 2) {
        appendAnswerRecord(answers, q.id, {value, ratio});
      } else {
        appendAnswerRecord(answers, q.id, {value});
      }
    }
  }

 private:
  std::size_t cell(int i, int j) const { return static_cast<std::size_t>(j) * size_[0] + i; }

  // Cell (i, j) takes the pixel in column int(i·rx) of row int(j·ry), rows from the bottom:
  // the light from green, the ratio from red.
  void sample(const Texture& image) {
    const float rx = size_[0] > 1
                         ? static_cast<float>(image.width - 1) / static_cast<float>(size_[0] - 1)
                         : 0.0f;
    const float ry = size_[1] > 1
                         ? static_cast<float>(image.height - 1) / static_cast<float>(size_[1] - 1)
                         : 0.0f;
    for (int j = 0; j < size_[1]; ++j) {
      const int row = std::min(image.height - 1, static_cast<int>(static_cast<float>(j) * ry));
      const std::uint8_t* pixels =
          image.rgba.data() + static_cast<std::size_t>(image.height - 1 - row) * image.width * 4;
      for (int i = 0; i < size_[0]; ++i) {
        const int column = std::min(image.width - 1, static_cast<int>(static_cast<float>(i) * rx));
        light_[cell(i, j)] = pixels[4 * column + 1];
        ratio_[cell(i, j)] = pixels[4 * column];
      }
    }
  }

  // A leaf of area `area` centred at (x, y): the cells of its ellipse in grid cells gain (or
  // lose) one leaf.
  void stampLeaf(float x, float y, float area, bool add) {
    if (area < 1e-7f) return;
    const float radius = static_cast<float>(std::sqrt(static_cast<double>(area) / M_PI));
    const float pt[2] = {x, y};
    int centre[2], half[2];
    for (int c = 0; c < 2; ++c) {
      centre[c] = floorIndex((pt[c] - corner_[c]) / range_[c] * static_cast<float>(size_[c]));
      const float h = radius / range_[c] * static_cast<float>(size_[c]) + 1;
      half[c] = h < 1e9f ? static_cast<int>(h) : 1'000'000'000;
    }
    // Only offsets that land in the grid can change a count.
    const long uFrom = std::max<long>(-half[0], -static_cast<long>(centre[0]));
    const long uTo = std::min<long>(half[0], static_cast<long>(size_[0]) - centre[0]);
    const long vFrom = std::max<long>(-half[1], -static_cast<long>(centre[1]));
    const long vTo = std::min<long>(half[1], static_cast<long>(size_[1]) - centre[1]);
    const float hx2 = static_cast<float>(static_cast<long>(half[0]) * half[0]);
    const float hy2 = static_cast<float>(static_cast<long>(half[1]) * half[1]);
    for (long v = vFrom; v < vTo; ++v) {
      for (long u = uFrom; u < uTo; ++u) {
        if (static_cast<float>(u * u) / hx2 + static_cast<float>(v * v) / hy2 > 1) continue;
        std::uint8_t& o =
            leaves_[cell(static_cast<int>(centre[0] + u), static_cast<int>(centre[1] + v))];
        if (add && o < 255) ++o;
        if (!add && o > 0) --o;
      }
    }
  }

  int size_[2] = {512, 512};
  float corner_[2] = {-1, -1};
  float range_[2] = {2, 2};
  float transmittance_ = 0.6f;
  bool removeOldLeaves_ = false;
  bool zIsUp_ = true;
  std::vector<std::uint8_t> light_, ratio_, leaves_;
  std::array<float, 256> powers_{};
};

}  // namespace

std::unique_ptr<EnvironmentProgram> makeClover(const CommunicationFile& file,
                                               const ProgramCommand& command,
                                               Diagnostics& diagnostics) {
  return std::make_unique<Clover>(file, command, diagnostics);
}

}  // namespace hirsute::programs
