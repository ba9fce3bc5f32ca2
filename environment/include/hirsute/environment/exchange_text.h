// The text that travels between cpfg and an environmental program, both ways (section 3.6 of
// the specification): query records and the control line from the L-system's side, answer
// records back. The master side (the query pass) writes queries and reads answers; the slave
// side (every environmental program, built in or not) reads queries and writes answers, as
// vlab's communication library does, so that the in-process programs see exactly the numbers
// the original programs decode from the text.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/environment/communication_file.h"
#include "hirsute/interpreter/environment_queries.h"

namespace hirsute {

// ---- master side --------------------------------------------------------------------------

// Appends the record of one ?E with identifier `id` to `batch`.
void appendQueryRecord(std::string& batch, unsigned long id, const EnvironmentQuery& q,
                       const CommunicationFile& file);
// The control line that ends a batch sent in one piece (flags 5), and the exit line.
std::string batchEndLine(int step);
inline constexpr std::string_view kExitLine = "Control: 8 0\n";

// One answer record: the identifier and the values, unset ones empty.
struct AnswerRecord {
  unsigned long id = 0;
  std::vector<std::optional<float>> values;
};
// The answer records of `text` up to its control line, read as cpfg does (atof to float).
// Lines that are not records (no `E`, an id that is not a whole number, parentheses left open or
// holding what is not a number) are returned in `rejected`.
std::vector<AnswerRecord> parseAnswers(std::string_view text,
                                       std::vector<std::string>* rejected = nullptr);

// ---- slave side ---------------------------------------------------------------------------

struct ModuleValues {
  std::string symbols;                       // "E", or the following module's one or two
  std::vector<std::optional<float>> values;  // unset for an empty piece between commas
  float value(std::size_t i, float otherwise = 0) const {
    return i < values.size() && values[i] ? *values[i] : otherwise;
  }
};

struct EnvironmentQueryRecord {
  unsigned long id = 0;
  ModuleValues module;
  ModuleValues following;
  // Per turtle value (TurtleValue order): what was read, and how many values the format
  // declares (the programs check this count, not what the line held).
  std::array<std::array<float, 3>, kTurtleValues> turtle{};
  std::array<int, kTurtleValues> counts{};
};

// Reads query records as the slave side of vlab's library does; stale turtle components survive
// from one record to the next, as they do there.
class QueryReader {
 public:
  explicit QueryReader(const CommunicationFile& file) : file_(file) {}
  // Reads the records of `text` into `out` (appending) up to a control line; returns its flags
  // (-1 if the text ends without one).
  int read(std::string_view text, std::vector<EnvironmentQueryRecord>& out);

 private:
  CommunicationFile file_;
  std::array<std::array<float, 3>, kTurtleValues> stale_{};
};

// Appends an answer record: `<id> E(v1,…)`, unset values empty; nothing for no values.
void appendAnswerRecord(std::string& answers, unsigned long id,
                        const std::vector<std::optional<float>>& values);
inline constexpr std::string_view kAnswersEndLine = "Control: 5\n";

}  // namespace hirsute
