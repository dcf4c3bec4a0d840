#include "experiments/run/initial_perturbation.hpp"

#include <cmath>
#include <cstdint>

namespace drape {

namespace {

// SplitMix64 (Steele, Lea, Flood 2014): fully specified, so a seed gives the same numbers on
// every platform and library (std's distributions are implementation-defined).
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : m_state(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (m_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1) with 53 random bits.
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t m_state;
};

}  // namespace

void perturb_initial_positions(const Perturbation& p, double spacing,
                               const ConstraintSet& constraints, Eigen::VectorXd& y) {
  perturb_positions(p, 0, spacing, constraints, y);
}

void perturb_positions(const Perturbation& p, std::uint64_t stream, double spacing,
                       const ConstraintSet& constraints, Eigen::VectorXd& y) {
  if (p.position <= 0.0) return;
  // Stream 0 is the seed itself (the initial perturbation of every earlier ensemble); stream k
  // starts from SplitMix64's k-th output of the seed, a sequence no other stream shares.
  std::uint64_t state = p.seed;
  if (stream > 0) {
    SplitMix64 streams(p.seed ^ 0x5851f42d4c957f2dULL);
    for (std::uint64_t k = 0; k < stream; ++k) state = streams.next();
  }
  SplitMix64 rng(state);
  const double a = p.position * spacing;
  const auto n = static_cast<int>(y.size() / 6);
  for (int i = 0; i < n; ++i) {
    // Every particle draws its three numbers, fixed or not, so that one particle's offset does
    // not depend on which others are fixed.
    for (int d = 0; d < 3; ++d) {
      double r;
      if (p.gaussian) {
        // Box-Muller; 1 - unit() is in (0, 1], so the log is finite.
        const double u1 = 1.0 - rng.unit(), u2 = rng.unit();
        r = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
      } else {
        r = 2.0 * rng.unit() - 1.0;
      }
      if (!constraints.is_fixed(i)) y[3 * i + d] += a * r;
    }
  }
}

}  // namespace drape
