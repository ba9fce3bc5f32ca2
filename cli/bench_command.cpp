// `hirsute bench`: figures measured on the command line. `bench ccd FILE.csv…` runs the
// continuous collision detection over query files with ground truth (docs/dynamics.md) and
// prints, per file and in total, the queries, false negatives, false positives and the time per
// query.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "command.h"
#include "hirsute/hairs/dynamics/ccd_query_file.h"
#include "hirsute/core/diagnostic.h"

namespace hirsute::cli {
namespace {

// Each file's queries are run again until this much time has passed, so that the time per query
// of a small file is not the clock's resolution.
constexpr double kMinimumTimedSeconds = 0.05;
constexpr int kMaximumPasses = 10000;

struct BenchCcdOptions {
  std::vector<std::string> files;
  double eta = 0;
  double tolerance = dynamics::CcdOptions{}.relativeTolerance;
};

struct Tally {
  std::size_t queries = 0, falseNegatives = 0, falsePositives = 0;
  double seconds = 0;  // for all the queries once
};

void printTally(const std::string& name, const Tally& tally) {
  const double microseconds =
      tally.queries == 0 ? 0.0 : tally.seconds * 1e6 / static_cast<double>(tally.queries);
  std::printf("%s: %zu queries, %zu false negatives, %zu false positives, %.2f us/query\n",
              name.c_str(), tally.queries, tally.falseNegatives, tally.falsePositives,
              microseconds);
}

Tally measure(const dynamics::CcdQueryFile& file, const dynamics::CcdOptions& options) {
  using Clock = std::chrono::steady_clock;
  Tally tally;
  tally.queries = file.queries.size();
  for (const dynamics::CcdQuery& query : file.queries) {
    const bool contact = dynamics::runCcdQuery(file.kind, query, options).contact;
    tally.falseNegatives += query.collides && !contact;
    tally.falsePositives += !query.collides && contact;
  }
  if (file.queries.empty()) return tally;
  int passes = 0;
  const auto start = Clock::now();
  double elapsed = 0;
  do {
    for (const dynamics::CcdQuery& query : file.queries) {
      // A call into another library, with its allocations: never optimised away.
      dynamics::runCcdQuery(file.kind, query, options);
    }
    ++passes;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < kMinimumTimedSeconds && passes < kMaximumPasses);
  tally.seconds = elapsed / passes;
  return tally;
}

int runBenchCcd(const BenchCcdOptions& o) {
  // Every file is read before any is run: bad input prints its error and no figures.
  std::vector<dynamics::CcdQueryFile> files;
  try {
    for (const std::string& name : o.files) files.push_back(dynamics::readCcdQueryFile(name));
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return kExitBadInput;
  }
  dynamics::CcdOptions options;
  options.minimumSeparation = o.eta;
  options.relativeTolerance = o.tolerance;
  Tally total;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const Tally tally = measure(files[i], options);
    printTally(o.files[i], tally);
    total.queries += tally.queries;
    total.falseNegatives += tally.falseNegatives;
    total.falsePositives += tally.falsePositives;
    total.seconds += tally.seconds;
  }
  printTally("total", total);
  return kExitOk;
}

// A finite number >= 0, said in words.
const CLI::Validator kNonNegative(
    [](std::string& text) -> std::string {
      double value = 0;
      std::size_t used = 0;
      try {
        value = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || !std::isfinite(value) || value < 0) {
        return "expected a number >= 0, found \"" + text + "\"";
      }
      return {};
    },
    "NUMBER >= 0");

}  // namespace

void registerBenchCommand(CLI::App& app, Action& action) {
  CLI::App* bench = app.add_subcommand("bench", "Measure Hirsute's algorithms and print figures");
  bench->require_subcommand(1);

  auto options = std::make_shared<BenchCcdOptions>();
  CLI::App* ccd = bench->add_subcommand(
      "ccd",
      "Run the continuous collision detection over CCD query files with ground truth (in folders "
      "named edge-edge or vertex-face) and print queries, false negatives, false positives and "
      "microseconds per query, per file and in total");
  ccd->add_option("files", options->files, "Query files (.csv)")->required();
  ccd->add_option("--eta", options->eta,
                  "Minimum separation: a contact is any time the primitives come within it in "
                  "every coordinate (default 0)")
      ->check(kNonNegative);
  ccd->add_option("--tolerance", options->tolerance,
                  "How near a near miss may come and still be reported, relative to the query's "
                  "size (default 1e-6)")
      ->check(kNonNegative);
  ccd->callback([options, &action] { action = [options] { return runBenchCcd(*options); }; });
}

}  // namespace hirsute::cli
