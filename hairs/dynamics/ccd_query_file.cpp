// Reading CCD query files: exact rationals rounded to the nearest double, with the rounding
// error kept so that the CCD can cover it.
#include "hirsute/hairs/dynamics/ccd_query_file.h"

#include <gmpxx.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <memory>
#include <string_view>

#include "hirsute/core/diagnostic.h"
#include "hirsute/core/input_file.h"

namespace hirsute::dynamics {
namespace {

constexpr int kColumns = 7;
constexpr int kRowsPerQuery = 8;

struct Field {
  std::string_view text;
  int column;  // 1-based
};

class Reader {
 public:
  explicit Reader(const std::filesystem::path& path)
      : file_(std::make_shared<const std::string>(path.string())) {}

  [[noreturn]] void fail(int line, int column, const std::string& message) const {
    throw DiagnosticError(SourceLocation{file_, line, column}, message);
  }

  std::vector<Field> split(std::string_view text, int line) const {
    std::vector<Field> fields;
    std::size_t begin = 0;
    for (;;) {
      const std::size_t comma = text.find(',', begin);
      const std::size_t end = comma == std::string_view::npos ? text.size() : comma;
      fields.push_back(Field{text.substr(begin, end - begin), static_cast<int>(begin) + 1});
      if (comma == std::string_view::npos) break;
      begin = comma + 1;
      if (fields.size() == kColumns) {
        fail(line, static_cast<int>(begin) + 1,
             "a query row has 7 comma-separated integers, this one has more");
      }
    }
    if (fields.size() != kColumns) {
      fail(line, static_cast<int>(text.size()) + 1,
           "a query row has 7 comma-separated integers, this one has " +
               std::to_string(fields.size()));
    }
    return fields;
  }

  mpz_class integer(const Field& field, int line) const {
    std::string_view digits = field.text;
    if (!digits.empty() && (digits.front() == '-' || digits.front() == '+'))
      digits.remove_prefix(1);
    if (digits.empty())
      fail(line, field.column, "expected an integer, found \"" + std::string(field.text) + "\"");
    for (std::size_t i = 0; i < digits.size(); ++i) {
      if (digits[i] < '0' || digits[i] > '9') {
        fail(line, field.column + static_cast<int>(field.text.size() - digits.size() + i),
             "expected an integer, found \"" + std::string(field.text) + "\"");
      }
    }
    if (digits.size() > kMaxCcdQueryDigits) {
      fail(line, field.column,
           "an integer of more than " + std::to_string(kMaxCcdQueryDigits) + " digits");
    }
    mpz_class value(std::string(digits), 10);
    return field.text.front() == '-' ? mpz_class(-value) : value;
  }

  // The double nearest to numerator/denominator, and how far it lies from it (rounded up).
  double coordinate(const Field& numerator, const Field& denominator, int line,
                    double& roundingError) const {
    const mpz_class n = integer(numerator, line), d = integer(denominator, line);
    if (d == 0) fail(line, denominator.column, "a zero denominator");
    mpq_class exact(n, d);
    exact.canonicalize();
    // mpq's conversion truncates towards zero; the nearest double is it or its neighbour away
    // from zero.
    double value = exact.get_d();
    if (!std::isfinite(value) || std::abs(value) > 0x1p1000) {
      fail(line, numerator.column, "a coordinate beyond the range the CCD computes in");
    }
    const double away = std::nextafter(value, exact > 0 ? INFINITY : -INFINITY);
    mpq_class error = abs(exact - mpq_class(value));
    const mpq_class awayError = abs(exact - mpq_class(away));
    if (awayError < error) {
      value = away;
      error = awayError;
    }
    double bound = error.get_d();
    if (mpq_class(bound) < error) bound = std::nextafter(bound, INFINITY);
    roundingError = std::max(roundingError, bound);
    return value;
  }

  bool truth(const Field& field, int line) const {
    if (field.text == "0") return false;
    if (field.text == "1") return true;
    fail(line, field.column,
         "the ground truth is 0 or 1, found \"" + std::string(field.text) + "\"");
  }

  const std::shared_ptr<const std::string>& file() const { return file_; }

 private:
  std::shared_ptr<const std::string> file_;
};

// The lines of a file read through its descriptor, each at most a given length: a line that
// runs on is refused when it passes the length, not after it was read whole.
class LineSource {
 public:
  enum class Result { Line, End, TooLong, Failed };

  explicit LineSource(int fd) : fd_(fd) {}

  // The next line without its '\n'; TooLong once it holds more than `maxLength` characters.
  Result next(std::string& line, std::size_t maxLength) {
    line.clear();
    for (;;) {
      if (at_ == filled_) {
        if (ended_) return line.empty() ? Result::End : Result::Line;
        const ssize_t n = ::read(fd_, buffer_.data(), buffer_.size());
        if (n < 0) {
          if (errno == EINTR) continue;
          failure_ = std::strerror(errno);
          return Result::Failed;
        }
        at_ = 0;
        filled_ = static_cast<std::size_t>(n);
        ended_ = n == 0;
        continue;
      }
      const char* begin = buffer_.data() + at_;
      const char* newline = static_cast<const char*>(std::memchr(begin, '\n', filled_ - at_));
      const std::size_t take = newline ? static_cast<std::size_t>(newline - begin) : filled_ - at_;
      if (line.size() + take > maxLength) return Result::TooLong;
      line.append(begin, take);
      at_ += take;
      if (newline) {
        ++at_;
        return Result::Line;
      }
    }
  }
  const std::string& failure() const { return failure_; }

 private:
  int fd_;
  std::array<char, 1 << 16> buffer_{};
  std::size_t at_ = 0, filled_ = 0;
  bool ended_ = false;
  std::string failure_;
};

}  // namespace

CcdQueryFile readCcdQueryFile(const std::filesystem::path& path) {
  Reader reader(path);
  CcdQueryFile result;
  const std::string folder = path.parent_path().filename().string();
  if (folder == "edge-edge") {
    result.kind = CcdQueryKind::EdgeEdge;
  } else if (folder == "vertex-face") {
    result.kind = CcdQueryKind::VertexFace;
  } else {
    throw DiagnosticError(SourceLocation{reader.file(), 0, 0},
                          "cannot tell the query kind: a query file lies in a folder named "
                          "edge-edge or vertex-face, this one is in \"" +
                              folder + "\"");
  }
  // A regular file only: a FIFO would wait for a writer, and a device such as /dev/zero never
  // ends.
  std::string failure;
  const FileDescriptor fd = openInputFile(path, failure);
  if (!fd) throw DiagnosticError(SourceLocation{reader.file(), 0, 0}, "cannot read: " + failure);
  LineSource lines(fd.get());

  std::string text;
  int line = 0, row = 0;
  CcdQuery query;
  for (;;) {
    const LineSource::Result got = lines.next(text, kMaxCcdQueryLineLength + 1);
    if (got == LineSource::Result::End) break;
    if (got == LineSource::Result::Failed) {
      throw DiagnosticError(SourceLocation{reader.file(), 0, 0},
                            "cannot read the file: " + lines.failure());
    }
    ++line;
    if (got == LineSource::Result::TooLong) {
      reader.fail(line, 1,
                  "a line longer than " + std::to_string(kMaxCcdQueryLineLength) + " characters");
    }
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.size() > kMaxCcdQueryLineLength) {
      reader.fail(line, 1,
                  "a line longer than " + std::to_string(kMaxCcdQueryLineLength) + " characters");
    }
    const std::vector<Field> fields = reader.split(text, line);
    if (row == 0) {
      query = CcdQuery{};
      query.line = line;
    }
    Eigen::Vector3d& vertex = row < 4 ? query.motion.start[row] : query.motion.end[row - 4];
    for (int k = 0; k < 3; ++k) {
      vertex[k] = reader.coordinate(fields[2 * k], fields[2 * k + 1], line, query.roundingError);
    }
    const bool collides = reader.truth(fields[6], line);
    if (row == 0) {
      query.collides = collides;
    } else if (collides != query.collides) {
      reader.fail(line, fields[6].column,
                  "the ground truth differs from the query's first row (line " +
                      std::to_string(query.line) + ")");
    }
    if (++row == kRowsPerQuery) {
      result.queries.push_back(query);
      row = 0;
    }
  }
  if (row != 0) {
    reader.fail(query.line, 1,
                "the file ends inside the query that starts here: it has " + std::to_string(row) +
                    " of its 8 rows");
  }
  return result;
}

CcdResult runCcdQuery(CcdQueryKind kind, const CcdQuery& query, CcdOptions options) {
  options.minimumSeparation += 2 * query.roundingError;
  return kind == CcdQueryKind::EdgeEdge ? edgeEdgeCcd(query.motion, options)
                                        : vertexFaceCcd(query.motion, options);
}

}  // namespace hirsute::dynamics
