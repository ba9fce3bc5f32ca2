// The floor under models/bench/loops.l: its blocks written in C++ and compiled with the project,
// run on the same leaves for the same steps, with the same libm calls and the same power operator
// (power.h, with fused multiply-adds where the processor has them), parameters rounded to float
// between steps as the string stores them. An evaluator that does the model's work as it is
// written (these libm calls, leaf by leaf), interpreted or compiled, cannot run the model's blocks
// in less time than this program: it is what the model's arithmetic costs on this machine.
//
//   hirsute_loops_native_bench [--threads N] [--check FILE.str] [--libm-pow]
//
// It prints its own time (the leaves split among N threads, default: one a core; the leaves are
// independent, so no thread waits for another). With --check it compares its final string with
// FILE.str, the string `hirsute derive models/bench/loops.l` wrote, value by value as the writer
// prints them (%g), and exits 1 on a difference: the floor is of the same computation. With
// --libm-pow every ^ calls libm's pow, as cpfg's evaluator does: the floor under cpfg's run.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "hirsute/lsys/power.h"

namespace {

// loops.l's #defines.
constexpr int kSteps = 105;
constexpr int kBuild = 15;
constexpr int kTerms = 6;
constexpr double kDegree = M_PI / 180.0;

// The exponents 2 and 3, hidden from the compiler: knowing them, it would turn the std::pow(x,
// 2.0) that power() falls back on into x*x, which libm's pow is not always (blocks' exponents
// are values, for the evaluator as for cpfg).
double opaque(double y) {
  asm("" : "+x"(y));
  return y;
}

// power.h's ^, with fused multiply-adds where the processor has them, as the machine code of
// native_code.h calls it.
[[gnu::target("fma")]] double powerWithFma(double x, double y) {
  return hirsute::powerFused(x, y);
}
double powerWithout(double x, double y) {
  return hirsute::power(x, y);
}
// libm's pow for every ^, as cpfg computes it (--libm-pow).
double libmPow(double x, double y) {
  return std::pow(x, y);
}
double (*power)(double, double) = __builtin_cpu_supports("fma") ? &powerWithFma : &powerWithout;

struct Leaf {
  float x, y, k;
};

// One step of P(x,y,k): the pre-condition block, the condition, the post-condition block and the
// successor, as models/bench/loops.l writes them (left to right, as the evaluator computes).
Leaf step(Leaf leaf) {
  const double two = opaque(2), three = opaque(3);
  const double x = leaf.x, y = leaf.y, k = leaf.k;
  double s = 0;
  double i = 1;
  while (i <= kTerms) {
    const double divisor = i * i;
    if (i == 0 || divisor == 0) throw std::runtime_error("division by zero");
    s = s + std::sin(i * x * 57.3 * kDegree) / i +
        power(std::cos(i * y * 40 * kDegree), two) / divisor + std::sqrt(i + std::fabs(x * y));
    i = i + 1;
  }
  if (!(s > 0)) return Leaf{leaf.x, leaf.y, static_cast<float>(k + 1)};
  double r = s;
  double j = 0;
  do {
    const double divisor = 3 * power(r, two);
    if (divisor == 0) throw std::runtime_error("division by zero");
    r = r - (power(r, three) - s) / divisor;
    j = j + 1;
  } while (j < 8);
  const double h = std::sqrt(x * x + y * y) + std::exp(-k * 0.01);
  return Leaf{static_cast<float>(x + 0.01 * r), static_cast<float>(y * 0.99 + 0.001 * h),
              static_cast<float>(k + 1)};
}

// The string after the derivation: the G(n,i) steps make leaf i (in string order) at step
// kBuild + 1; every later step rewrites each leaf.
void derive(std::vector<Leaf>& leaves, std::size_t from, std::size_t to) {
  for (std::size_t i = from; i < to; ++i) {
    const auto index = static_cast<double>(static_cast<float>(i));
    Leaf leaf{static_cast<float>(0.1 + 0.0001 * index), static_cast<float>(0.2 + 0.00003 * index),
              0.0f};
    for (int s = kBuild + 2; s <= kSteps; ++s) leaf = step(leaf);
    leaves[i] = leaf;
  }
}

// The values of every module of a string in the writer's text, in order.
std::vector<std::string> valuesIn(const std::string& text) {
  std::vector<std::string> values;
  std::string current;
  bool inside = false;
  for (char c : text) {
    if (c == '(') {
      inside = true;
    } else if (inside && (c == ',' || c == ')')) {
      values.push_back(current);
      current.clear();
      inside = c == ',';
    } else if (inside) {
      current += c;
    }
  }
  return values;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"loops.l's blocks compiled natively: the floor under any evaluator"};
  int threads = 0;
  std::string check;
  app.add_option("--threads", threads, "Threads (0: one a core)")->check(CLI::Range(0, 64));
  app.add_option("--check", check, "A string of loops.l written by hirsute derive, to compare")
      ->check(CLI::ExistingFile);
  bool libm = false;
  app.add_flag("--libm-pow", libm, "Every ^ as libm's pow, as cpfg computes it (the same values)");
  CLI11_PARSE(app, argc, argv);
  if (libm) power = &libmPow;
  if (threads == 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  const std::size_t count = std::size_t{1} << kBuild;
  std::vector<Leaf> leaves(count);
  const auto started = std::chrono::steady_clock::now();
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) {
    workers.emplace_back(derive, std::ref(leaves), count * static_cast<std::size_t>(t) / threads,
                         count * static_cast<std::size_t>(t + 1) / threads);
  }
  derive(leaves, 0, count / static_cast<std::size_t>(threads));
  for (std::thread& w : workers) w.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf(
      "loops.l's blocks compiled natively%s: %.3f s on %d thread%s (%zu leaves, %d steps)\n",
      libm ? ", libm's pow for ^" : "", seconds, threads, threads == 1 ? "" : "s", count,
      kSteps - kBuild - 1);

  if (check.empty()) return 0;
  std::ifstream in(check);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::vector<std::string> theirs = valuesIn(text);
  std::vector<std::string> ours;
  char buffer[64];
  for (const Leaf& leaf : leaves) {
    for (float v : {leaf.x, leaf.y, leaf.k}) {
      std::snprintf(buffer, sizeof buffer, "%g", static_cast<double>(v));
      ours.emplace_back(buffer);
    }
  }
  if (ours != theirs) {
    std::size_t at = 0;
    while (at < ours.size() && at < theirs.size() && ours[at] == theirs[at]) ++at;
    std::fprintf(stderr,
                 "%s: differs from the native computation at value %zu of %zu (%s, not %s)\n",
                 check.c_str(), at, ours.size(), at < theirs.size() ? theirs[at].c_str() : "none",
                 at < ours.size() ? ours[at].c_str() : "none");
    return 1;
  }
  std::printf("the same string as %s (%zu values)\n", check.c_str(), ours.size());
  return 0;
}
