// Open L-systems: a collision model (honda81) and a light model (chiba), derived with the
// built-in program in this process and with the same program as a process of its own
// (hirsute-environment) over each of cpfg's transports. Prints the seconds of each run, the
// queries sent and queries per second, the in-process speed-up, and whether every run derived
// the same string.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "hirsute/environment/environment.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/lsys/string_writer.h"

namespace fs = std::filesystem;
using namespace hirsute;

namespace {

struct BenchModel {
  const char* name;
  const char* program;
  const char* lsystem;
  const char* spec;
  const char* position;
};

// A bush whose every apex forks each step unless honda81 finds another apex at least as
// vigorous within 0.6: the collisions keep the number of apices growing slowly.
const BenchModel kCollision{
    "collision (honda81)", "honda81",
    "Lsystem: 1\nderivation length: 40\nAxiom: A(1)?E(1)\n"
    "A(v)?E(x) : x==1 --> [+(20)FA(v*0.999)?E(v*0.999)][-(20)FA(v*1.001)?E(v*1.001)]\n"
    "A(v)?E(x) : x==0 --> *\nendlsystem\n",
    "radius: 0.6\n3d case: on\n", "turtle position: %.4f %.4f %.4f\n"};

// A binary tree of 512 leaf clusters asking chiba, each step, for the light through the canopy
// from 128 sky directions.
const BenchModel kLight{
    "light (chiba)", "chiba",
    "Lsystem: 1\nderivation length: 14\nAxiom: A(9)\n"
    "A(n) : n>0 --> F(2)[+(35)/(90)A(n-1)][-(35)/(90)A(n-1)]\nA(n) : n==0 --> ?E(1)\nendlsystem\n",
    "grid size: 16x16x16\nnumber of samples: 128\nlower to upper ratio: 0\n"
    "estimate intersection area: on\ntransmittance: 0.2\n",
    "turtle position:P:%.4g %.4g %.4g\n"};

struct Result {
  double seconds = 0;
  std::size_t queries = 0, batches = 0;
  std::string string;
};

Result derive(const fs::path& folder, bool external, const char* transport) {
  Diagnostics diagnostics;
  Model model = loadModel(folder / "model.l", std::nullopt, diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  Derivation derivation(model.program, evaluator, diagnostics);
  ModelResources resources;
  {
    std::ofstream e(folder / "model.e");
    e << "executable: ./" << folder.filename().string()
      << " model.spec\ncommunication type: " << transport << "\n"
      << std::ifstream(folder / "position").rdbuf();
  }
  const auto start = std::chrono::steady_clock::now();
  EnvironmentOptions options;
  options.forceExternal = external;
  std::unique_ptr<Environment> environment =
      openEnvironment(folder / "model.e", diagnostics, options);
  installQueryPass(derivation, resources, diagnostics, environment.get());
  derivation.run();
  Result r;
  r.queries = environment->queriesSent();
  r.batches = environment->batchesSent();
  environment.reset();  // the external program's end counts too
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* memory = open_memstream(&buffer, &size);
  {
    StringWriter writer(memory, StringFormat::Compact);
    derivation.emit(writer, false);
    writer.finish();
  }
  std::fclose(memory);
  r.string.assign(buffer, size);
  std::free(buffer);
  return r;
}

void bench(const BenchModel& m, const fs::path& root) {
  // The folder is named after the program: its link to hirsute-environment has that name.
  const fs::path folder = root / m.program;
  fs::create_directories(folder);
  std::ofstream(folder / "model.l") << m.lsystem;
  std::ofstream(folder / "model.spec") << m.spec;
  std::ofstream(folder / "position") << m.position;
  fs::create_symlink(HIRSUTE_ENVIRONMENT_SERVER, folder / m.program);
  const Result builtin = derive(folder, false, "pipes");
  std::printf("%s: %zu queries in %zu batches, %zu bytes of string\n", m.name, builtin.queries,
              builtin.batches, builtin.string.size());
  std::printf("  %-22s %9.3f s  %12.0f queries/s\n", "built in", builtin.seconds,
              builtin.queries / builtin.seconds);
  for (const char* transport : {"pipes", "files", "memory"}) {
    Result external;
    try {
      external = derive(folder, true, transport);
    } catch (const DiagnosticError& e) {
      std::printf("  %-22s %s\n", (std::string("process over ") + transport).c_str(),
                  e.diagnostic().message.c_str());
      continue;
    }
    std::printf("  %-22s %9.3f s  %12.0f queries/s  built in %.1fx faster, %s string\n",
                (std::string("process over ") + transport).c_str(), external.seconds,
                external.queries / external.seconds, external.seconds / builtin.seconds,
                external.string == builtin.string ? "same" : "DIFFERENT");
  }
}

}  // namespace

int main() {
  const fs::path root =
      fs::temp_directory_path() / ("hirsute-environment-bench-" + std::to_string(getpid()));
  fs::create_directories(root);
  try {
    bench(kCollision, root);
    bench(kLight, root);
  } catch (const DiagnosticError& e) {
    std::fprintf(stderr, "%s\n", e.diagnostic().text().c_str());
    fs::remove_all(root);
    return 2;
  }
  fs::remove_all(root);
  return 0;
}
