#include "hirsute/environment/environment_program.h"

#include <cmath>
#include <functional>

#include "hirsute/core/model_folder.h"
#include "programs/builtin_programs.h"

namespace hirsute {

ProgramCommand parseProgramCommand(const CommunicationFile& file) {
  ProgramCommand command;
  const std::string text = file.executable.value_or("");
  struct Word {
    std::string text;
    int column;
  };
  std::vector<Word> words;
  for (std::size_t i = 0; i < text.size();) {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
    const std::size_t from = i;
    while (i < text.size() && text[i] != ' ' && text[i] != '\t') ++i;
    if (i > from) words.push_back(Word{text.substr(from, i - from), static_cast<int>(from)});
  }
  if (!words.empty() && words.back().text == "&") words.pop_back();  // cpfg drops a final &
  for (const Word& w : words) command.words.push_back(w.text);
  if (words.empty()) return command;
  command.program = words[0].text;
  for (std::size_t i = 1; i < words.size(); ++i) {
    const std::string& w = words[i].text;
    if (w == "-e" || w == "-ext" || w == "-k" || w == "-h") {
      ++i;  // the option's value
      continue;
    }
    command.specificationWhere = file.executableWhere;
    command.specificationWhere.column += words[i].column;
    // The specification is read beside the .e and must stay beneath its folder
    // (model_folder.h): an absolute name, a `..`, a link out or a FIFO is an error at it.
    const ModelFolder folder(file.file.parent_path());
    const std::string refused = folder.refusal(w);
    if (!refused.empty())
      throw DiagnosticError(command.specificationWhere, "cannot open '" + w + "': " + refused);
    command.specification = folder.pathOf(w);
    break;
  }
  return command;
}

std::string BuiltinProgram::exchange(const std::string& batch) {
  const int flags = reader_.read(batch, pending_);
  std::string answers;
  // Parts of a split batch are collected; the last part (flag 4) or the exit (8) ends it.
  if (flags < 0 || (flags & 12) != 0) {
    answer(pending_, answers);
    pending_.clear();
  }
  answers += kAnswersEndLine;
  return answers;
}

void BuiltinProgram::reject(const std::string& why) {
  if (rejected_) return;
  rejected_ = true;
  diagnostics_.warn(SourceLocation{std::make_shared<const std::string>(name_), 0, 0},
                    why + "; such queries get no answer");
}

namespace {

using Factory = std::function<std::unique_ptr<EnvironmentProgram>(
    const CommunicationFile&, const ProgramCommand&, Diagnostics&)>;
struct Builtin {
  const char* name;
  Factory make;
};

const std::vector<Builtin>& builtins() {
  static const std::vector<Builtin> table = {
      {"honda81", programs::makeHonda81}, {"ecosystem", programs::makeEcosystem},
      {"clover", programs::makeClover},   {"chiba", programs::makeChiba},
      {"density", programs::makeDensity},
  };
  return table;
}

}  // namespace

const std::vector<std::string>& builtinProgramNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Builtin& b : builtins()) out.push_back(b.name);
    return out;
  }();
  return names;
}

std::unique_ptr<EnvironmentProgram> makeBuiltinProgram(const CommunicationFile& file,
                                                       Diagnostics& diagnostics) {
  const ProgramCommand command = parseProgramCommand(file);
  const std::string name = std::filesystem::path(command.program).filename().string();
  for (const Builtin& b : builtins()) {
    if (name == b.name) return b.make(file, command, diagnostics);
  }
  return nullptr;
}

namespace programs {

int floorIndex(double v) {
  const double f = std::floor(v);
  if (!(f > -1e9)) return -1'000'000'000;
  return f > 1e9 ? 1'000'000'000 : static_cast<int>(f);
}

std::vector<KeywordLine> readSpecification(const ProgramCommand& command,
                                           const CommunicationFile& file) {
  if (!command.specification) {
    throw DiagnosticError(file.executableWhere,
                          command.program + " needs its specification file on the executable line");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(*command.specification, ec)) {
    throw DiagnosticError(command.specificationWhere, "cannot read " + command.program +
                                                          "'s specification file " +
                                                          command.specification->string());
  }
  return readKeywordLines(*command.specification, 254);
}

}  // namespace programs
}  // namespace hirsute
