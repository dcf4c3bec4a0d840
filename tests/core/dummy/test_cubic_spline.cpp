// The spline moments: exact on the functions a cubic spline must reproduce, close on smooth ones.
#include "core/dummy/cubic_spline.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace drape::detail {
namespace {

TEST(CubicSpline, NaturalSplineIsExactOnLinesAndInterpolatesItsKnots) {
  const std::vector<double> knots{1.0, 0.9, 0.75, 0.7, 0.4};  // decreasing, uneven
  Eigen::MatrixXd values(5, 2);
  for (int k = 0; k < 5; ++k) values.row(k) << 2.0 - 3.0 * knots[k], std::sin(4.0 * knots[k]);
  const Eigen::MatrixXd moments = natural_spline_moments(knots, values);
  EXPECT_LT(moments.col(0).cwiseAbs().maxCoeff(), 1e-12);  // a line has no curvature
  EXPECT_EQ(moments(0, 1), 0.0);
  EXPECT_EQ(moments(4, 1), 0.0);
  // C1 at the interior knots: the slopes of the two segments agree.
  for (int k = 1; k < 4; ++k) {
    const double h0 = knots[k - 1] - knots[k], h1 = knots[k] - knots[k + 1];
    const SplinePoint left = cubic_segment(values(k - 1, 1), values(k, 1), moments(k - 1, 1),
                                           moments(k, 1), h0, 1.0);
    const SplinePoint right = cubic_segment(values(k, 1), values(k + 1, 1), moments(k, 1),
                                            moments(k + 1, 1), h1, 0.0);
    EXPECT_NEAR(left.value, values(k, 1), 1e-14);
    EXPECT_NEAR(left.d1, right.d1, 1e-12);
    EXPECT_NEAR(left.d2, right.d2, 1e-12);
  }
}

TEST(CubicSpline, PeriodicSplineIsExactOnConstantsAndNearOnASine) {
  const int m = 32;
  const double h = 2.0 * M_PI / m;
  Eigen::MatrixXd values(2, m);
  for (int j = 0; j < m; ++j) values.col(j) << 0.3, std::sin(j * h);
  const Eigen::MatrixXd moments = periodic_spline_moments(values);
  EXPECT_LT(moments.row(0).cwiseAbs().maxCoeff(), 1e-12);
  // The moments approximate -sin to O(h^2).
  for (int j = 0; j < m; ++j) EXPECT_NEAR(moments(1, j), -std::sin(j * h), h * h);
  const SplinePoint mid = cubic_segment(values(1, 3), values(1, 4), moments(1, 3), moments(1, 4), h, 0.5);
  EXPECT_NEAR(mid.value, std::sin(3.5 * h), 5.0 / 384.0 * std::pow(h, 4) * 2.0);
  EXPECT_NEAR(mid.d1, std::cos(3.5 * h), h * h * h);
}

}  // namespace
}  // namespace drape::detail
