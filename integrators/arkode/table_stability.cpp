#include "integrators/arkode/table_stability.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace drape {

namespace {

using ComplexVector = Eigen::VectorXcd;

Eigen::MatrixXd matrix_of(const ButcherTableau& t) {
  const std::size_t s = t.c.size();
  Eigen::MatrixXd a(s, s);
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j) a(i, j) = t.A[i][j];
  return a;
}

Eigen::VectorXd weights_of(const ButcherTableau& t) {
  return Eigen::Map<const Eigen::VectorXd>(t.b.data(), static_cast<Eigen::Index>(t.b.size()));
}

// The stage values Y = (I - z A)^-1 1 of y' = lambda y, y0 = 1 (R_int(z) = 1 + z A Y = Y), by
// forward substitution written in w = 1/z, Y_i = (w + sum_j<i a_ij Y_j) / (w - a_ii), which
// stays exact as z -> -inf (w = 0) where the form in z loses digits in proportion to |z| (1e-4
// at z = -1e12 measured). An explicit row (a_ii = 0) keeps Y_i = 1 + z sum_j<i a_ij Y_j; for
// w = 0 it is finite only with that sum 0, as in the first stage of an ESDIRK.
ComplexVector stage_values(const ButcherTableau& t, std::complex<double> w) {
  const std::size_t s = t.c.size();
  ComplexVector y(static_cast<Eigen::Index>(s));
  for (std::size_t i = 0; i < s; ++i) {
    std::complex<double> known = 0.0;
    for (std::size_t j = 0; j < i; ++j) known += t.A[i][j] * y(j);
    if (t.A[i][i] != 0.0)
      y(i) = (w + known) / (w - t.A[i][i]);
    else if (w != 0.0)
      y(i) = 1.0 + known / w;
    else
      y(i) = known == 0.0 ? 1.0 : std::numeric_limits<double>::infinity();
  }
  return y;
}

// R(z) = 1 + z b^T Y from the stage values Y = stage_values(t, 1 / z) (real weights: Eigen's
// conjugating dot product is the plain one).
std::complex<double> stability_from_stages(const Eigen::VectorXcd& weights, std::complex<double> z,
                                           const ComplexVector& stages) {
  return 1.0 + z * weights.dot(stages);
}

// e_m(X), the sum of X's principal minors of order m.
double principal_minor_sum(const Eigen::MatrixXd& x, int m) {
  double sum = 0.0;
  const int s = static_cast<int>(x.rows());
  for (unsigned mask = 0; mask < (1u << s); ++mask) {
    if (__builtin_popcount(mask) != m) continue;
    std::vector<int> rows;
    for (int i = 0; i < s; ++i)
      if (mask & (1u << i)) rows.push_back(i);
    sum += Eigen::MatrixXd(x(rows, rows)).determinant();
  }
  return sum;
}

// R(-inf) from R(z) = det(I - z A + z 1 b^T) / det(I - z A) (Hairer and Wanner, Solving ODEs II,
// Prop. IV.3.2): with m nonzero a_ii the denominator has degree m, the numerator's coefficient
// of (-z)^k is e_k(A - 1 b^T), so the limit is e_m(A - 1 b^T) / e_m(A), infinite when a higher
// coefficient of the numerator is not zero.
double stiff_limit_of(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  const int s = static_cast<int>(a.rows());
  const int m = static_cast<int>((a.diagonal().array() != 0.0).count());
  const Eigen::MatrixXd x = a - Eigen::VectorXd::Ones(s) * b.transpose();
  for (int k = m + 1; k <= s; ++k)
    if (std::abs(principal_minor_sum(x, k)) > 1e-12) return std::numeric_limits<double>::infinity();
  return std::abs(principal_minor_sum(x, m) / principal_minor_sum(a, m));
}

// Samples of the imaginary axis, y from 1e-3 to 1e6 with 400 per decade.
std::vector<double> imaginary_axis_samples() {
  std::vector<double> y;
  for (int k = -3 * 400; k <= 6 * 400; ++k) y.push_back(std::pow(10.0, k / 400.0));
  return y;
}

// Why |A_I^-1|: at h omega >> 1 a stiff spring's stage positions are pinned near its rest length
// and the stage forces follow from them, h k_I = A_I^-1 (Y_I - y_n - h a_I1 k_1) for the implicit
// stages I, the relation of Runge-Kutta methods on index-3 constraints (Hairer and Wanner,
// Solving ODEs II, sec. VII.4; Lubich 1993, "Integration of stiff mechanical systems by
// Runge-Kutta methods", ZAMP 44): a stage position error of the geometric nonlinearity reaches
// the forces, and so the velocities, multiplied by up to this norm.
double implicit_inverse_norm(const Eigen::MatrixXd& a) {
  std::vector<Eigen::Index> implicit;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    if (a(i, i) != 0.0) implicit.push_back(i);
  const Eigen::MatrixXd block = a(implicit, implicit);
  const Eigen::MatrixXd inverse = block.triangularView<Eigen::Lower>().solve(
      Eigen::MatrixXd::Identity(block.rows(), block.cols()));
  return inverse.cwiseAbs().rowwise().sum().maxCoeff();
}

}  // namespace

std::complex<double> stability_function(const ButcherTableau& t, std::complex<double> z) {
  return stability_from_stages(weights_of(t).cast<std::complex<double>>(), z,
                               stage_values(t, 1.0 / z));
}

std::vector<std::complex<double>> stage_stability_functions(const ButcherTableau& t,
                                                            std::complex<double> z) {
  const ComplexVector stages = stage_values(t, 1.0 / z);
  return {stages.data(), stages.data() + stages.size()};
}

TableStability table_stability(const ButcherTableau& t) {
  const Eigen::MatrixXd a = matrix_of(t);
  const Eigen::VectorXd b = weights_of(t);
  TableStability out;
  out.min_weight = b.minCoeff();
  // Burrage and Butcher 1979, "Stability criteria for implicit Runge-Kutta methods", SIAM J.
  // Numer. Anal. 16(1): b >= 0 and M positive semidefinite make the method B-stable (contractive
  // on every dissipative problem), whatever the stiffness.
  const Eigen::MatrixXd m =
      b.asDiagonal() * a + a.transpose() * b.asDiagonal() - b * b.transpose();
  out.algebraic_stability = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m).eigenvalues()(0);
  const std::size_t s = t.c.size();
  out.stage_max_imaginary_axis.assign(s, 0.0);
  const Eigen::VectorXcd weights = b.cast<std::complex<double>>();
  for (const double y : imaginary_axis_samples()) {
    // One forward substitution a sample gives both R(iy) and the stage values.
    const std::complex<double> z{0.0, y};
    const ComplexVector stages = stage_values(t, 1.0 / z);
    out.max_imaginary_axis =
        std::max(out.max_imaginary_axis, std::abs(stability_from_stages(weights, z, stages)));
    for (std::size_t i = 0; i < s; ++i)
      out.stage_max_imaginary_axis[i] =
          std::max(out.stage_max_imaginary_axis[i], std::abs(stages(static_cast<Eigen::Index>(i))));
  }
  out.stiff_limit = stiff_limit_of(a, b);
  for (const auto& r : stage_values(t, 0.0)) out.stage_stiff_limit.push_back(std::abs(r));
  out.max_coefficient = a.cwiseAbs().maxCoeff();
  out.nodes_in_unit_interval =
      std::all_of(t.c.begin(), t.c.end(), [](double c) { return c >= 0.0 && c <= 1.0; });
  out.implicit_inverse_norm = implicit_inverse_norm(a);
  return out;
}

}  // namespace drape
