// hirsute-environment: Hirsute's built-in environmental programs as a process of their own, for
// cpfg or any master that speaks its protocol (files, shared memory or pipes, through
// libcomm.a). Started under a program's name (a link called honda81, chiba, …) it is that
// program; otherwise the first argument names it:
//
//   hirsute-environment PROGRAM [-e FILE.e] SPECIFICATION
//   honda81 -e FILE.e density.spec          (a link to hirsute-environment)
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "comm_lib.h"
#include "hirsute/environment/communication_file.h"
#include "hirsute/environment/environment_program.h"

using namespace hirsute;

extern "C" void Message(const char* format, ...) {
  va_list args;
  va_start(args, format);
  std::vfprintf(stderr, format, args);
  va_end(args);
}

namespace {

bool isBuiltin(const std::string& name) {
  for (const std::string& b : builtinProgramNames()) {
    if (b == name) return true;
  }
  return false;
}

int usage() {
  std::cerr << "usage: hirsute-environment PROGRAM [-e FILE.e] SPECIFICATION\n  PROGRAM:";
  for (const std::string& b : builtinProgramNames()) std::cerr << ' ' << b;
  std::cerr << '\n';
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string efile;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "-e") == 0) efile = argv[i + 1];
  }
  CSInitialize(&argc, &argv);  // takes -e, -k, -ext and -h out of argv
  std::vector<std::string> words(argv, argv + argc);
  std::string program = std::filesystem::path(words[0]).filename().string();
  if (!isBuiltin(program)) {
    if (words.size() < 2 || !isBuiltin(words[1])) return usage();
    program = words[1];
    words.erase(words.begin());
  }
  Diagnostics diagnostics(&std::cerr);
  std::unique_ptr<EnvironmentProgram> builtin;
  try {
    CommunicationFile file;
    if (!efile.empty()) file = readCommunicationFile(efile, diagnostics);
    std::string executable = program;
    for (std::size_t i = 1; i < words.size(); ++i) executable += " " + words[i];
    file.executable = executable;
    builtin = makeBuiltinProgram(file, diagnostics);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return 2;
  }
  std::vector<char> line(1 << 20);
  bool running = true;
  while (running) {
    CSBeginTransmission();
    std::string batch;
    int flags = -1;
    int master = 0;
    while (CSGetString(&master, line.data(), static_cast<int>(line.size()))) {
      batch += line.data();
      batch += '\n';
      if (std::strncmp(line.data(), "Control:", 8) == 0) {
        flags = std::atoi(line.data() + 8);
        break;
      }
    }
    if (flags < 0 || (flags & 8) != 0) break;  // the master has gone, or said goodbye
    std::string answers;
    try {
      answers = builtin->exchange(batch);
    } catch (const DiagnosticError& e) {
      std::cerr << e.diagnostic().text() << '\n';
      return 2;
    }
    answers.erase(answers.rfind("Control:"));  // CSEndTransmission ends the answers itself
    CSSendString(0, answers.data());
    CSEndTransmission();
  }
  CTerminate();
  return 0;
}
