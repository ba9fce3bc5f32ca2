// The `.e` communication file of cpfg's open L-systems (cpfg -e FILE.e): which environmental
// program answers the ?E modules, over which transport, and which turtle values travel with
// each query, as printf formats kept byte for byte.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

enum class Transport { Files, Memory, Pipes, Sockets };

// One `turtle …:` line: the format applied to the values, the number of conversions in it
// (each `%` not followed by `%`) and the offset of the first conversion, which the program
// skips before it reads the numbers.
struct TurtleFormat {
  bool present = false;
  std::string format;
  int conversions = 0;
  std::size_t firstConversion = 0;
};

// The turtle values in the order their lines follow a query's module line.
enum TurtleValue { kPosition, kHeading, kLeft, kUp, kLineWidth, kScaleFactor, kTurtleValues };

// A module named by `interpreted modules:`: a symbol with a given parameter count, or any.
struct InterpretedModule {
  char symbol = 0;
  int parameters = -1;  // -1: any number
};

struct CommunicationFile {
  std::filesystem::path file;
  std::optional<std::string> executable;  // the rest of the `executable:` line
  SourceLocation executableWhere;
  Transport transport = Transport::Pipes;
  int chunkLimit = 100;  // queries per part of a batch (files 1000)
  std::array<TurtleFormat, kTurtleValues> turtle;
  bool followingModule = true;
  bool interpretAll = false;
  std::vector<InterpretedModule> interpreted;
  std::vector<int> whenInterpret;
  bool verbose = false;
  std::string remoteHost;
};

// Reads `file` as cpfg does (section 2 of the specification): keywords up to the first `:` or
// TAB, compared exactly; unknown keywords are warnings. A format that printf could not apply to
// its values safely (a conversion other than a floating one, more conversions than values), an
// unsupported exchange (`strings only`, `binary data`) or a file that cannot be read is an
// error at its line and column.
CommunicationFile readCommunicationFile(const std::filesystem::path& file,
                                        Diagnostics& diagnostics);
// The same for text already read; `file` names it in diagnostics, and its folder is where the
// executable line's specification file is found.
CommunicationFile parseCommunicationFile(std::string_view text, const std::filesystem::path& file,
                                         Diagnostics& diagnostics);

}  // namespace hirsute
