// Conformance runner: derives every model of the conformance set (real cpfg models with cpfg's
// own strings) and compares our string with cpfg's `expected.str` (and `expected.homo.str` with
// the homomorphism), newlines removed. Prints one line per model and a final count; exits 1 when
// a model that must match does not, 77 (skip) when the folder is absent.
//
// Every model must match, except the understood differences named below. Open L-systems
// (environment=yes) run against their environmental program: a built-in one, or the model's
// own, built with its makefile against Hirsute's communication library.
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/environment/environment.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/lsys/string_writer.h"

namespace fs = std::filesystem;
using namespace hirsute;

namespace {

struct Row {
  std::string id, lfile, vfile, environment, notes;
  int steps = 0;
};

std::vector<Row> readIndex(const fs::path& file) {
  std::ifstream in(file);
  std::vector<Row> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, '\t')) cells.push_back(cell);
    if (cells.size() < 8) continue;
    Row r{cells[0], cells[1], cells[2], cells[6], cells.size() > 8 ? cells[8] : "", std::stoi(cells[5])};
    rows.push_back(r);
  }
  return rows;
}

std::string readFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string withoutNewlines(std::string text) {
  std::erase(text, '\n');
  return text;
}

// Splits a string in cpfg's text format into modules: a symbol and its parameter list.
std::vector<std::string> modules(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < text.size();) {
    std::size_t j = i + 1;
    if (j < text.size() && text[j] == '(') {
      std::size_t close = text.find(')', j);
      j = close == std::string::npos ? text.size() : close + 1;
    }
    out.push_back(text.substr(i, j - i));
    i = j;
  }
  return out;
}

// The model's .e file (cpfg -e), the only one in its folder.
std::optional<fs::path> communicationFile(const fs::path& folder) {
  std::optional<fs::path> found;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".e") continue;
    if (found) return std::nullopt;
    found = entry.path();
  }
  return found;
}

// A model whose environmental program is its own (`executable: ./NAME`, built by NAME.mak)
// runs in a scratch folder beside copies of the model's files (links out of a model's folder are
// not followed, docs/files.md): the program is built there with
// the model's own makefile against Hirsute's communication library. Returns the scratch
// folder's .e file, or nullopt with `why` set.
std::vector<fs::path> scratchFolders;  // removed when the runner ends

std::optional<fs::path> buildModelProgram(const fs::path& folder, const fs::path& efile, std::string& why) {
  Diagnostics quiet;
  CommunicationFile e = readCommunicationFile(efile, quiet);
  const ProgramCommand command = parseProgramCommand(e);
  const std::string name = fs::path(command.program).filename().string();
  if (command.program.rfind("./", 0) != 0 || !fs::exists(folder / (name + ".mak"))) {
    why = "its environmental program " + command.program + " is neither built in nor built by the model";
    return std::nullopt;
  }
  fs::path scratch = fs::temp_directory_path() / ("hirsute-conformance-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  scratchFolders.push_back(scratch);
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() == ".a") continue;  // a prebuilt library of another platform
    fs::copy(entry.path(), scratch / entry.path().filename(), fs::copy_options::recursive);
  }
  const std::string make = "cd '" + scratch.string() + "' && make -s -f " + name + ".mak LOCAL='" +
                           HIRSUTE_COMM_LIBRARY_DIR + "' >make.log 2>&1";
  if (std::system(make.c_str()) != 0) {
    why = "building " + name + " with " + name + ".mak failed (see " + (scratch / "make.log").string() + ")";
    return std::nullopt;
  }
  return scratch / efile.filename();
}

// The derived string (after the homomorphism when asked), in cpfg's format without newlines.
// `environment` is the model's .e file for an open L-system.
std::string derive(const fs::path& folder, const Row& row, bool homomorphism, bool batchMode,
                   const std::optional<fs::path>& environmentFile = std::nullopt) {
  Diagnostics diagnostics;  // warnings are not printed here
  std::optional<fs::path> view;
  if (row.vfile != "-") view = folder / row.vfile;
  ModelOptions modelOptions;
  modelOptions.defineFunctionSetNames = !batchMode;
  Model model = loadModel(folder / row.lfile, view, diagnostics, modelOptions);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  DerivationOptions options;
  options.steps = row.steps;
  Derivation derivation(model.program, evaluator, diagnostics, options);
  // Query modules (?P ?H ?L ?U) are filled by the turtle before each step, and the
  // environment answers ?E in the same pass.
  std::unique_ptr<Environment> environment;
  if (environmentFile) environment = openEnvironment(*environmentFile, diagnostics);
  std::optional<ModelResources> resources;
  if (model.program.usesQueries || environment) {
    resources = loadModelResources(view, ColorFiles{}, diagnostics);
    installQueryPass(derivation, *resources, diagnostics, environment.get());
  }
  derivation.run();
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* memory = open_memstream(&buffer, &size);
  {
    StringWriter writer(memory, StringFormat::Compact);
    writer.setStrings(&model.program.strings);
    derivation.emit(writer, homomorphism);
    writer.finish();
  }
  std::fclose(memory);
  std::string text(buffer, size);
  std::free(buffer);
  return withoutNewlines(text);
}

// Models whose difference from cpfg is understood and accepted for now, with the reason
// ({"model-id", "why"}). None at present: every model must match.
struct KnownDifference {
  const char* id;
  const char* reason;
};
constexpr std::array<KnownDifference, 0> kKnownDifferences{};

const char* knownDifference(const std::string& id) {
  for (const KnownDifference& k : kKnownDifferences) {
    if (id == k.id) return k.reason;
  }
  return nullptr;
}

// "match", or where the strings first differ.
std::string compare(const std::string& ours, const std::string& expected) {
  if (ours == expected) return "match";
  std::vector<std::string> a = modules(ours), b = modules(expected);
  std::size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  std::ostringstream s;
  s << "differs at module " << i << ": ours " << (i < a.size() ? a[i] : "<end>") << ", cpfg "
    << (i < b.size() ? b[i] : "<end>") << " (" << a.size() << " vs " << b.size() << " modules)";
  return s.str();
}

}  // namespace

int main(int argc, char** argv) {
  fs::path root = argc > 1 ? argv[1] : "../shared/conformance";
  if (!fs::exists(root / "index.tsv")) {
    std::cout << "conformance: " << root.string() << " is absent; skipping (it holds cpfg's outputs)\n";
    return 77;
  }
  int passed = 0, failed = 0, excused = 0, skipped = 0;
  for (const Row& row : readIndex(root / "index.tsv")) {
    fs::path folder = root / row.id;
    std::optional<fs::path> environmentFile;
    if (row.environment == "yes") {
      // An open L-system runs against its environment when its program is built in.
      // A program of the model's own is built with its makefile first.
      environmentFile = communicationFile(folder);
      std::string why;
      if (!environmentFile) {
        why = "no single .e file in its folder";
      } else {
        Diagnostics quiet;
        CommunicationFile e = readCommunicationFile(*environmentFile, quiet);
        if (!makeBuiltinProgram(e, quiet)) environmentFile = buildModelProgram(folder, *environmentFile, why);
      }
      if (!why.empty()) {
        std::cout << row.id << ": skipped (" << why << ")\n";
        ++skipped;
        continue;
      }
    }
    for (bool homomorphism : {false, true}) {
      fs::path expectedFile = folder / (homomorphism ? "expected.homo.str" : "expected.str");
      if (!fs::exists(expectedFile)) continue;
      std::string label = row.id + (homomorphism ? " (homomorphism)" : "");
      // cpfg wrote these homomorphism strings in its batch mode (-g), which reads the .l before
      // the .v: function-set names were undefined. We reproduce that mode for them.
      bool batchMode = homomorphism && row.notes.find("-g reads .l before .v") != std::string::npos;
      if (batchMode) label += " [as cpfg -g: function-set names undefined]";
      std::string result;
      try {
        result = compare(derive(folder, row, homomorphism, batchMode, environmentFile),
                         withoutNewlines(readFile(expectedFile)));
      } catch (const DiagnosticError& e) {
        result = "error: " + e.diagnostic().text();
      }
      std::string excuse;
      if (result != "match") {
        if (const char* reason = knownDifference(row.id)) {
          excuse = reason;
        }
      }
      if (result == "match") {
        ++passed;
        std::cout << label << ": match\n";
      } else if (!excuse.empty()) {
        ++excused;
        std::cout << label << ": " << result << " [expected: " << excuse << "]\n";
      } else {
        ++failed;
        std::cout << label << ": " << result << '\n';
      }
    }
  }
  for (const fs::path& scratch : scratchFolders) fs::remove_all(scratch);
  std::cout << passed << " passed, " << failed << " failed";
  if (excused) std::cout << " (" << excused << " known differences explained above)";
  if (skipped) std::cout << ", " << skipped << " skipped";
  std::cout << '\n';
  return failed == 0 ? 0 : 1;
}
