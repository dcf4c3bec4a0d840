// Chebyshev semi-iterative weights (Wang 2015, equation 12): the recurrence's first terms and its
// limit, the fixed point of omega = 4 / (4 - rho^2 omega), 2 / (1 + sqrt(1 - rho^2)).
#include "integrators/acceleration/chebyshev.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace drape {
namespace {

TEST(Chebyshev, FirstWeightsInClosedForm) {
  const double rho = 0.9;
  EXPECT_EQ(chebyshev_omega(1, rho, 0.0), 1.0);
  const double omega2 = chebyshev_omega(2, rho, 1.0);
  EXPECT_DOUBLE_EQ(omega2, 2.0 / (2.0 - 0.81));
  EXPECT_DOUBLE_EQ(chebyshev_omega(3, rho, omega2), 4.0 / (4.0 - 0.81 * omega2));
  EXPECT_EQ(chebyshev_omega(5, 0.0, 1.7), 1.0) << "rho = 0: the plain iteration";
}

// omega_{k+1} = g(omega_k) with g increasing and omega_2 above g's fixed point: the weights fall
// from omega_2 to it, all of them above 1 and below 2.
TEST(Chebyshev, WeightsFallFromTheSecondToTheOptimalOverRelaxation) {
  for (const double rho : {0.3, 0.9, 0.99}) {
    const double limit = 2.0 / (1.0 + std::sqrt(1.0 - rho * rho));
    double omega = chebyshev_omega(2, rho, 1.0);
    EXPECT_GT(omega, limit);
    for (int k = 3; k <= 400; ++k) {
      const double next = chebyshev_omega(k, rho, omega);
      EXPECT_LE(next, omega) << "rho " << rho << ", k " << k;
      EXPECT_GE(next, limit * (1.0 - 1e-15)) << "rho " << rho << ", k " << k;
      omega = next;
    }
    EXPECT_NEAR(omega, limit, 1e-12) << "rho " << rho;
    EXPECT_GT(omega, 1.0);
    EXPECT_LT(omega, 2.0);
  }
}

}  // namespace
}  // namespace drape
