#include "core/dummy/cubic_spline.hpp"

#include <Eigen/LU>
#include <cmath>

namespace drape::detail {

// The tridiagonal system of the interior moments, h_{k-1} M_{k-1} + 2 (h_{k-1} + h_k) M_k +
// h_k M_{k+1} = 6 (slope_k - slope_{k-1}), by the Thomas algorithm for every column at once
// (the matrix is strictly diagonally dominant, so no pivoting is needed).
Eigen::MatrixXd natural_spline_moments(const std::vector<double>& knots,
                                       const Eigen::MatrixXd& values) {
  const int n = static_cast<int>(knots.size());
  Eigen::MatrixXd moments = Eigen::MatrixXd::Zero(n, values.cols());
  if (n < 3) return moments;
  std::vector<double> h(static_cast<std::size_t>(n - 1));
  for (int k = 0; k + 1 < n; ++k) h[k] = std::abs(knots[k + 1] - knots[k]);
  const int interior = n - 2;
  std::vector<double> diag(interior), upper(interior);
  Eigen::MatrixXd rhs(interior, values.cols());
  for (int i = 0; i < interior; ++i) {
    const int k = i + 1;
    diag[i] = 2.0 * (h[k - 1] + h[k]);
    upper[i] = h[k];
    rhs.row(i) = 6.0 * ((values.row(k + 1) - values.row(k)) / h[k] -
                        (values.row(k) - values.row(k - 1)) / h[k - 1]);
  }
  for (int i = 1; i < interior; ++i) {
    const double w = h[i] / diag[i - 1];  // sub-diagonal entry of row i is h_{k-1} = h[i]
    diag[i] -= w * upper[i - 1];
    rhs.row(i) -= w * rhs.row(i - 1);
  }
  moments.row(interior) = rhs.row(interior - 1) / diag[interior - 1];
  for (int i = interior - 2; i >= 0; --i)
    moments.row(i + 1) = (rhs.row(i) - upper[i] * moments.row(i + 2)) / diag[i];
  return moments;
}

// M_{j-1} + 4 M_j + M_{j+1} = 6 (R_{j+1} - 2 R_j + R_{j-1}) / h^2, cyclic: one small dense LU,
// factored once for every section.
Eigen::MatrixXd periodic_spline_moments(const Eigen::MatrixXd& values) {
  const int m = static_cast<int>(values.cols());
  const double h = 2.0 * M_PI / m;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
  Eigen::MatrixXd rhs(m, values.rows());
  for (int j = 0; j < m; ++j) {
    const int prev = (j + m - 1) % m, next = (j + 1) % m;
    a(j, j) += 4.0;
    a(j, prev) += 1.0;
    a(j, next) += 1.0;
    rhs.row(j) = 6.0 / (h * h) * (values.col(next) - 2.0 * values.col(j) + values.col(prev)).transpose();
  }
  return Eigen::PartialPivLU<Eigen::MatrixXd>(a).solve(rhs).transpose();
}

}  // namespace drape::detail
