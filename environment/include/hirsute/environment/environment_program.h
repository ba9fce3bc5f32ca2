// An environmental program as the query pass sees it: a batch of query records goes in, the
// answer records come back. The built-in programs run in this process; a program that is not
// built in runs as a process of its own (external_program.h).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "hirsute/environment/communication_file.h"
#include "hirsute/environment/exchange_text.h"

namespace hirsute {

class EnvironmentProgram {
 public:
  virtual ~EnvironmentProgram() = default;
  // The program's name for messages.
  virtual const std::string& name() const = 0;
  // One batch, or one part of a batch: query records ending with a control line in; answer
  // records ending with `Control: 5` out.
  virtual std::string exchange(const std::string& batch) = 0;

  // How large one part of a batch may be (cpfg splits larger batches into parts): bytes of
  // query text, queries, and a bound on the bytes of their answers. Unlimited in-process.
  struct PartLimits {
    std::size_t bytes = static_cast<std::size_t>(-1);
    std::size_t queries = static_cast<std::size_t>(-1);
    std::size_t answerBytes = static_cast<std::size_t>(-1);
  };
  virtual PartLimits partLimits() const { return {}; }
};

// The `executable:` line taken apart as cpfg's programs take their command line: the program,
// its own options (-e FILE, -ext X, -k KEY, -h HOST) and the first remaining argument, the
// specification file (resolved against the folder of the .e file, where cpfg runs).
struct ProgramCommand {
  std::string program;             // as written
  std::vector<std::string> words;  // every word, the program first
  std::optional<std::filesystem::path> specification;
  SourceLocation specificationWhere;  // its word on the executable line
};
ProgramCommand parseProgramCommand(const CommunicationFile& file);

// A program that reads its records with the slave side and answers a whole batch at once.
class BuiltinProgram : public EnvironmentProgram {
 public:
  BuiltinProgram(std::string name, const CommunicationFile& file, Diagnostics& diagnostics)
      : name_(std::move(name)), reader_(file), diagnostics_(diagnostics) {}
  const std::string& name() const override { return name_; }
  std::string exchange(const std::string& batch) override;

 protected:
  // Appends the answers to `batch` (in query order) to `answers`.
  virtual void answer(const std::vector<EnvironmentQueryRecord>& batch, std::string& answers) = 0;
  // Warns once about queries the program rejects (they get no answer), as the originals do.
  void reject(const std::string& why);
  Diagnostics& diagnostics() { return diagnostics_; }

 private:
  std::string name_;
  QueryReader reader_;
  Diagnostics& diagnostics_;
  std::vector<EnvironmentQueryRecord> pending_;  // records of a batch split in parts
  bool rejected_ = false;
};

// The built-in program named by the executable line's program (its file name: `honda81`,
// `/usr/local/bin/honda81` and `./honda81` all pick honda81), reading its specification file;
// null when no built-in has that name.
std::unique_ptr<EnvironmentProgram> makeBuiltinProgram(const CommunicationFile& file,
                                                       Diagnostics& diagnostics);
// The names of the built-in programs.
const std::vector<std::string>& builtinProgramNames();

}  // namespace hirsute
