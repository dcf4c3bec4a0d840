#include "experiments/run/initial_perturbation.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

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

// One coordinate's draw: uniform in [-1, 1] or, Box-Muller, standard normal (1 - unit() is in
// (0, 1], so the log is finite).
double draw(SplitMix64& rng, bool gaussian) {
  if (!gaussian) return 2.0 * rng.unit() - 1.0;
  const double u1 = 1.0 - rng.unit(), u2 = rng.unit();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

// Adds a * draw to the three coordinates of every free particle in y's block at `offset` (0:
// positions, 3N: velocities). Every particle draws its three numbers, fixed or not, so that one
// particle's offset does not depend on which others are fixed.
void add_noise(SplitMix64& rng, bool gaussian, double a, const ConstraintSet& constraints,
               Eigen::Index offset, Eigen::VectorXd& y) {
  const auto n = static_cast<int>(y.size() / 6);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const double r = draw(rng, gaussian);
      if (!constraints.is_fixed(i)) y[offset + 3 * i + d] += a * r;
    }
}

// The velocities' stream: a state no SplitMix64 output of the map streams' generator starts from
// but by chance.
constexpr std::uint64_t velocity_stream_key = 0xd1b54a32d192ed03ULL;

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
  add_noise(rng, p.gaussian, p.position * spacing, constraints, 0, y);
}

void stretch_initial_positions(double stretch, ConstraintSet& constraints, Eigen::VectorXd& y) {
  if (stretch == 0.0) return;
  const auto n = static_cast<int>(y.size() / 6);
  const auto x = [&](int i) { return y.segment<3>(3 * i); };
  const std::vector<int>& fixed = constraints.fixed_particles();
  Vec3 centre = Vec3::Zero();
  if (fixed.empty()) {
    for (int i = 0; i < n; ++i) centre += x(i);
    centre /= n;
  } else {
    for (const int i : fixed) centre += x(i);
    centre /= static_cast<double>(fixed.size());
  }
  for (int i = 0; i < n; ++i) x(i) = centre + (1.0 + stretch) * (x(i) - centre);
  for (const int i : std::vector<int>(fixed)) constraints.fix_at(i, x(i));
}

void perturb_initial_velocities(const Perturbation& p, const ConstraintSet& constraints,
                                Eigen::VectorXd& y) {
  if (p.velocity <= 0.0) return;
  SplitMix64 rng(p.seed ^ velocity_stream_key);
  add_noise(rng, p.gaussian, p.velocity, constraints, y.size() / 2, y);
}

void perturb_initial_state(const Perturbation& p, double spacing, ConstraintSet& constraints,
                           Eigen::VectorXd& y) {
  stretch_initial_positions(p.stretch, constraints, y);
  perturb_initial_positions(p, spacing, constraints, y);
  perturb_initial_velocities(p, constraints, y);
}

}  // namespace drape
