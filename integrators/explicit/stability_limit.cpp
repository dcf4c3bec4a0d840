#include "integrators/explicit/stability_limit.hpp"

// GCC 12's -Wuse-after-free flags Eigen's aligned_free as inlined into Spectra's
// UpperHessenbergEigen::doComputeEigenvectors, where a vector is resized and then freed: a false
// positive of its flow analysis (clang and GCC's sanitizers see no such use).
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuse-after-free"
#endif
#include <Spectra/GenEigsSolver.h>
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic pop
#endif

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace drape {

namespace {

// -dF/dx as Spectra's matrix operation: the exact Jacobian's product, its fixed rows zeroed
// (their columns meet only zeros in a start vector without fixed components, and stay so). The
// particles share one mass, so -M^-1 dF/dx has the same eigenvectors and eigenvalues divided by
// it; dividing afterwards keeps Arnoldi's arithmetic at the forces' scale, where a tiny mass
// (1e-300 kg) made the Krylov vectors' norms overflow and the Schur decomposition fail.
class StiffnessOperator {
 public:
  using Scalar = double;
  StiffnessOperator(const ClothSystem& system, ConstVecRef x, ConstVecRef v,
                    const std::function<void(long)>& after_product)
      : m_system(system),
        m_x(x),
        m_v(v),
        m_after_product(after_product),
        m_zero(Eigen::VectorXd::Zero(x.size())),
        m_in(x.size()),
        m_out(x.size()) {}
  Eigen::Index rows() const { return m_x.size(); }
  Eigen::Index cols() const { return m_x.size(); }
  void perform_op(const double* in, double* out) const {
    m_in = Eigen::Map<const Eigen::VectorXd>(in, m_x.size());
    m_system.force_jacobian_times(m_x, m_v, m_in, m_zero, m_out, false);
    Eigen::Map<Eigen::VectorXd>(out, m_x.size()) = -m_out;
    if (m_after_product) m_after_product(++m_products);
  }

 private:
  const ClothSystem& m_system;
  ConstVecRef m_x, m_v;
  const std::function<void(long)>& m_after_product;
  mutable long m_products = 0;
  Eigen::VectorXd m_zero;
  mutable Eigen::VectorXd m_in, m_out;
};

// Arnoldi vectors kept: enough that the restarts filter a cluster of nearly equal fast modes (a
// large uniform cloth has many) in tens of iterations, where the power iteration took of the
// order of the particle count (10479 at 100 x 100).
constexpr Eigen::Index krylov_vectors = 30;

}  // namespace

ExplicitStabilityLimit explicit_stability_limit(const ClothSystem& system, ConstVecRef x,
                                                ConstVecRef v, int max_restarts,
                                                const std::function<void(long)>& after_product) {
  const Eigen::Index n3 = x.size();
  ExplicitStabilityLimit limit;
  const double none = std::numeric_limits<double>::infinity();
  const auto free_dofs = 3 * (static_cast<Eigen::Index>(system.num_particles()) -
                              static_cast<Eigen::Index>(system.constraints().fixed_particles().size()));
  if (free_dofs == 0) {  // nothing moves: no mode, no limit
    limit.undamped = limit.damped = none;
    return limit;
  }
  // A fixed seed: the same state gives the same answer.
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd start(n3);
  for (Eigen::Index k = 0; k < n3; ++k) start[k] = uniform(rng);
  system.constraints().zero_fixed(start);
  StiffnessOperator op(system, x, v, after_product);
  // Arnoldi's method (Lehoucq and Sorensen's implicit restarts, as ARPACK; Spectra), for a
  // Jacobian that need not be symmetric: the paper's contact force is not a potential's.
  Spectra::GenEigsSolver<StiffnessOperator> solver(
      op, 1, std::min(krylov_vectors, n3));
  solver.init(start.data());
  // The rightmost eigenvalue: the fastest oscillation, omega^2. A negative one is a mode that
  // grows by itself (a compressed spring buckling), no limit on the step.
  solver.compute(Spectra::SortRule::LargestReal, max_restarts, 1e-10);
  if (solver.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error("explicit_stability_limit: Arnoldi's method did not converge");
  limit.jacobian_products = static_cast<int>(solver.num_operations());
  const double mass = system.particle_mass();
  const double lambda = solver.eigenvalues()[0].real() / mass;  // omega^2
  limit.omega2_imaginary = solver.eigenvalues()[0].imag() / mass;
  Eigen::VectorXd u = solver.eigenvectors().col(0).real();
  u.normalize();
  Eigen::VectorXd w(n3);
  system.force_jacobian_times(x, v, Eigen::VectorXd::Zero(n3), u, w, false);
  limit.damping_rate = 0.0 - u.dot(w) / mass;  // +0, not -0, without damping
  limit.omega = std::sqrt(std::max(lambda, 0.0));
  const double c = limit.damping_rate;
  limit.undamped = limit.omega > 0.0 ? 2.0 / limit.omega : none;
  // The positive root of h^2 omega^2 + 2 h c - 4 = 0, (-c + sqrt(c^2 + 4 omega^2)) / omega^2,
  // written as 4 / (c + sqrt(c^2 + 4 omega^2)): no cancellation when c dominates, and hypot
  // keeps c^2 from overflowing for a very light cloth.
  limit.damped =
      lambda > 0.0 ? 4.0 / (c + std::hypot(c, 2.0 * std::sqrt(lambda))) : none;
  return limit;
}

}  // namespace drape
