#pragma once
// A small deterministic random source. std::normal_distribution differs between standard
// libraries, so the simulator draws from its own generator: the same seed gives the same
// bytes on every platform (up to libm's log/cos in the Gaussian).

#include <cmath>
#include <cstdint>

namespace hylo::sim {

/// SplitMix64 (Steele, Lea, Flood 2014): fast, passes BigCrush, trivially seedable.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}

  /// A stream derived from `seed` and a tag (session, scan index, ...), independent of the
  /// order in which streams are used.
  static Rng Derive(uint64_t seed, uint64_t tag_a, uint64_t tag_b = 0) {
    Rng mix(seed ^ (0x9E3779B97F4A7C15ULL * (tag_a + 1)));
    const uint64_t a = mix.NextU64();
    Rng mix2(a ^ (0xBF58476D1CE4E5B9ULL * (tag_b + 1)));
    return Rng(mix2.NextU64());
  }

  uint64_t NextU64() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, 1).
  double Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }

  /// Standard normal by Box-Muller (one of the pair is kept for the next call).
  double Gaussian() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = Uniform();
    while (u1 <= 1e-300) u1 = Uniform();
    const double u2 = Uniform();
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * M_PI * u2;
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }
  double Gaussian(double sigma) { return sigma * Gaussian(); }

 private:
  uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace hylo::sim
