#pragma once
// Random numbers that are the same on every platform: std::mt19937_64's sequence is fixed by
// the standard, but the std:: distributions are not, so the draws are made here.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace eco::sim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  /// A generator for one purpose (`stream`) of one seed, independent of the others.
  Rng(std::uint64_t seed, std::uint64_t stream) : engine_(mix(seed ^ mix(stream + 1))) {}

  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  bool chance(double p) { return uniform() < p; }
  int below(int n) { return static_cast<int>(uniform() * n); }
  /// A count with Poisson's law of mean `mean` (Knuth's product of uniforms; means up to ~100).
  int poisson(double mean) {
    const double floor = std::exp(-mean);
    int k = 0;
    for (double product = uniform(); product > floor; product *= uniform()) ++k;
    return k;
  }
  double normal() {  // Box-Muller
    const double u = 1.0 - uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * uniform());
  }

 private:
  static std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
  }
  std::mt19937_64 engine_;
};

}  // namespace eco::sim
