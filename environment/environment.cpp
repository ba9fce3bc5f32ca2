#include "hirsute/environment/environment.h"

#include "hirsute/environment/exchange_text.h"
#include "hirsute/environment/external_program.h"

namespace hirsute {
namespace {

// The bytes of a module in cpfg's packed string: the symbol, and `(` plus four bytes and a
// separator per parameter.
std::size_t packedSize(ModuleRef m) {
  const std::size_t n = m.parameterCount();
  return n == 0 ? 1 : 2 + 5 * n;
}

}  // namespace

Environment::Environment(CommunicationFile file, std::unique_ptr<EnvironmentProgram> program,
                         Diagnostics& diagnostics)
    : file_(std::move(file)), program_(std::move(program)), diagnostics_(diagnostics) {}

void Environment::beginPass(ModuleString& string, int step) {
  string_ = &string;
  step_ = step;
  batch_.clear();
  recordEnds_.clear();
  answerBounds_.clear();
  positions_.clear();
}

void Environment::query(const EnvironmentQuery& q) {
  unsigned long id = 1;  // a ?E made by the homomorphism: sent, its answer ignored
  if (q.position != EnvironmentQuery::kMadeByHomomorphism) {
    if (positions_.empty()) {
      id = 0;
    } else {
      std::size_t bytes = 0;
      for (std::size_t p = lastPosition_; p < q.position; p = string_->next(p))
        bytes += packedSize(string_->at(p));
      id = lastIdentifier_ + bytes;
    }
    lastPosition_ = q.position;
    lastIdentifier_ = id;
    positions_[id] = q.position;
  }
  appendQueryRecord(batch_, id, q, file_);
  recordEnds_.push_back(batch_.size());
  // `<id> E(` and `)\n`, and per value at most 12 characters of %g and a comma.
  answerBounds_.push_back(25 + 13 * q.count);
}

void Environment::endPass() {
  if (recordEnds_.empty()) return;  // the program is not woken for a pass without ?E
  queriesSent_ += recordEnds_.size();
  ++batchesSent_;
  // A batch larger than the program takes at once goes in parts, as cpfg splits it: the
  // control line of each part but the last says that more follow.
  const EnvironmentProgram::PartLimits limits = program_->partLimits();
  constexpr std::size_t kControlReserve = 25;
  std::size_t from = 0;
  bool first = true;
  while (from < recordEnds_.size()) {
    const std::size_t start = from == 0 ? 0 : recordEnds_[from - 1];
    std::size_t to = from + 1, answers = answerBounds_[from];
    while (to < recordEnds_.size() && to - from < limits.queries &&
           recordEnds_[to] - start + kControlReserve <= limits.bytes &&
           answers + answerBounds_[to] + kControlReserve <= limits.answerBytes) {
      answers += answerBounds_[to];
      ++to;
    }
    sendPart(from, to, first, to == recordEnds_.size());
    first = false;
    from = to;
  }
  batch_.clear();
  recordEnds_.clear();
  answerBounds_.clear();
}

void Environment::sendPart(std::size_t from, std::size_t to, bool first, bool last) {
  const std::size_t start = from == 0 ? 0 : recordEnds_[from - 1];
  std::string part = batch_.substr(start, recordEnds_[to - 1] - start);
  if (first && last) {
    part += batchEndLine(step_);
  } else {
    part += last    ? "Control: 4 " + std::to_string(step_) + "\n"
            : first ? "Control: 1 0\n"
                    : "Control: 0 0\n";
  }
  std::vector<std::string> rejected;
  const std::string answers = program_->exchange(part);
  const SourceLocation where{std::make_shared<const std::string>(file_.file.string()), 0, 0};
  for (const AnswerRecord& a : parseAnswers(answers, &rejected)) {
    if (a.id == 1) continue;
    auto found = positions_.find(a.id);
    if (found == positions_.end()) {
      diagnostics_.warn(where, program_->name() + " answered a query it was not sent (" +
                                   std::to_string(a.id) + "); the answer is ignored");
      continue;
    }
    const std::size_t count = string_->at(found->second).parameterCount();
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      if (i >= count) {
        if (!warnedRoom_) {
          diagnostics_.warn(where, "not enough room for " + std::to_string(a.values.size()) +
                                       " parameters coming from " + program_->name() +
                                       "; the extra values are dropped");
          warnedRoom_ = true;
        }
        break;
      }
      if (a.values[i]) string_->setParameter(found->second, i, *a.values[i]);
    }
  }
  if (!rejected.empty()) {
    throw DiagnosticError(file_.executableWhere, "environmental program " + program_->name() +
                                                     " answered a line that is not an answer record: '" +
                                                     rejected.front() + "'");
  }
}

std::unique_ptr<Environment> openEnvironment(const std::filesystem::path& file,
                                             Diagnostics& diagnostics,
                                             const EnvironmentOptions& options) {
  CommunicationFile e = readCommunicationFile(file, diagnostics);
  if (!e.executable) {
    diagnostics.warn(
        SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0},
        "no executable: line; the environment is ignored and ?E modules keep their values");
    return nullptr;
  }
  std::unique_ptr<EnvironmentProgram> program;
  if (!options.forceExternal) program = makeBuiltinProgram(e, diagnostics);
  if (!program) program = startExternalProgram(e, options.timeoutSeconds, diagnostics, options.log);
  return std::make_unique<Environment>(std::move(e), std::move(program), diagnostics);
}

}  // namespace hirsute
