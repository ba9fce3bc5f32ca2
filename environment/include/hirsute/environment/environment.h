// The L-system's side of an open L-system (cpfg -e FILE.e): collects the ?E modules the query
// pass meets into a batch, hands it to the environmental program at the end of the pass, and
// writes the answers into the parameters of the ?E modules, as cpfg does.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "hirsute/environment/communication_file.h"
#include "hirsute/environment/environment_program.h"
#include "hirsute/interpreter/environment_queries.h"
#include "hirsute/core/diagnostic.h"

namespace hirsute {

struct EnvironmentOptions {
  bool forceExternal = false;  // run the executable even when a built-in has its name
  int timeoutSeconds = 60;     // an external program that takes longer to answer is an error
  // -v: where an external program's command line is shown before it starts; none: not shown.
  std::ostream* log = nullptr;
};

class Environment : public EnvironmentQueries {
 public:
  Environment(CommunicationFile file, std::unique_ptr<EnvironmentProgram> program,
              Diagnostics& diagnostics);

  void beginPass(ModuleString& string, int step) override;
  void query(const EnvironmentQuery& q) override;
  void endPass() override;

  const CommunicationFile& file() const { return file_; }
  const EnvironmentProgram& program() const { return *program_; }
  std::size_t queriesSent() const { return queriesSent_; }
  std::size_t batchesSent() const { return batchesSent_; }

 private:
  CommunicationFile file_;
  std::unique_ptr<EnvironmentProgram> program_;
  Diagnostics& diagnostics_;
  ModuleString* string_ = nullptr;
  int step_ = 0;
  // The records of the pass: their text one after the other, where each ends, and a bound on
  // the bytes of each one's answer.
  std::string batch_;
  std::vector<std::size_t> recordEnds_;
  std::vector<std::size_t> answerBounds_;
  void sendPart(std::size_t from, std::size_t to, bool first, bool last);
  // cpfg's identifiers: the bytes of its packed string from the first ?E of the pass.
  std::size_t lastPosition_ = 0;
  unsigned long lastIdentifier_ = 0;
  std::unordered_map<unsigned long, std::size_t> positions_;  // identifier → E module
  std::size_t queriesSent_ = 0;
  std::size_t batchesSent_ = 0;
  bool warnedRoom_ = false;
};

// Reads the .e file and starts its program: the built-in of the executable's name, or else the
// executable as a process. Without an `executable:` line cpfg ignores the environment: a warning,
// and null.
std::unique_ptr<Environment> openEnvironment(const std::filesystem::path& file,
                                             Diagnostics& diagnostics,
                                             const EnvironmentOptions& options = {});

}  // namespace hirsute
