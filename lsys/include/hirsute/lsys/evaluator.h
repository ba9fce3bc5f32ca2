// The evaluator: runs compiled code against the state of one derivation (variables, arrays,
// random stream, user functions, open files).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <ostream>
#include <vector>

#include "hirsute/core/model_folder.h"
#include "hirsute/lsys/builtins.h"
#include "hirsute/lsys/code.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/program.h"
#include "hirsute/lsys/random_streams.h"

namespace hirsute {

struct ViewFunctions;

struct EvaluationLimits {
  // Iterations of while and do-while loops per run of one block; a runaway loop is an error.
  std::uint64_t maxLoopIterations = 10'000'000;
  // Files one model may have open at once.
  int maxOpenFiles = 32;
  // Bytes the blocks may write through fprintf, in all their files together; a runaway loop
  // that writes is an error at the call, not a full disk.
  std::uint64_t maxWrittenBytes = std::uint64_t{256} << 20;
};

class Evaluator {
 public:
  Evaluator(const Program& program, Diagnostics& diagnostics, const ViewFunctions* functions,
            std::filesystem::path modelFolder, std::ostream& printOut, EvaluationLimits limits = {});
  ~Evaluator();
  Evaluator(const Evaluator&) = delete;
  Evaluator& operator=(const Evaluator&) = delete;

  // Runs statements; returns the value left by an expression (0 when none).
  double run(const Code& code, double* frame);
  // Runs code that leaves `count` values; returns them (valid until the next run).
  const double* values(const Code& code, double* frame, std::size_t count);
  bool isTrue(const Code& condition, double* frame) {
    return condition.empty() || run(condition, frame) != 0;
  }

  // An evaluator of the same program, functions and limits for another thread, warning into
  // `diagnostics`, reading the variables of readVariablesOf(). Only for code that writes no
  // global variable or array and opens, prints and draws nothing (parallel_rewriting.h): it
  // has no arrays of its own, and no files or random stream.
  std::unique_ptr<Evaluator> fork(Diagnostics& diagnostics) const;
  // Takes the global and L-system variables of `other` as they are now, and reads its arrays
  // where they are, while `other` changes none of them.
  void readVariablesOf(const Evaluator& other) {
    shared_ = other.shared_;
    arrays_ = other.arrays_;
  }

  std::vector<double>& shared() { return shared_; }
  BlockRandom& random() { return *random_; }
  // Swaps in another random stream (the homomorphism's own, when it has a seed).
  void useRandom(BlockRandom* stream) { random_ = stream ? stream : &ownRandom_; }
  bool stopRequested() const { return stopRequested_; }
  void clearStop() { stopRequested_ = false; }
  const Program& program() const { return program_; }
  const SourceLocation& location(std::uint32_t where) const { return program_.locations[where]; }

 private:
  Evaluator(const Evaluator& parent, Diagnostics& diagnostics);  // fork()
  double call(Builtin id, const double* args, int count, std::uint32_t where);
  // Out of run()'s loop, so that its common cases keep their pointers in registers.
  [[gnu::noinline]] double* loadElement(const Instruction& in, double* top);
  [[gnu::noinline]] double* storeElement(const Instruction& in, double* top);
  [[gnu::noinline]] double modulo(double a, double b, std::uint32_t where) const;
  [[gnu::noinline]] double* scan(const Instruction& in, double* top);
  [[noreturn, gnu::cold, gnu::noinline]] void failLoop(std::uint32_t where) const;
  double openFile(const std::string& name, const std::string& mode, std::uint32_t where);
  std::FILE* file(double id, std::uint32_t where);
  std::string format(const std::string& format, const double* args, int count, std::uint32_t where);
  std::size_t elementIndex(std::int32_t array, const double* subscripts, int count, std::uint32_t where);
  [[noreturn]] void fail(std::uint32_t where, const std::string& message) const;

  const Program& program_;
  Diagnostics& diagnostics_;
  const ViewFunctions* functions_;
  ModelFolder modelFolder_;
  std::ostream& printOut_;
  EvaluationLimits limits_;
  std::vector<double> shared_;
  std::vector<std::vector<double>> ownArrays_;
  std::vector<std::vector<double>>* arrays_ = &ownArrays_;  // another's, in a fork
  std::vector<double> stack_;
  BlockRandom ownRandom_;
  BlockRandom* random_ = &ownRandom_;
  std::vector<std::FILE*> files_;
  std::uint64_t writtenBytes_ = 0;
  bool stopRequested_ = false;
};

}  // namespace hirsute
