#pragma once
// Chebyshev semi-iterative acceleration of a stationary iteration (Wang 2015, "A Chebyshev
// semi-iterative approach for accelerating projective and position-based dynamics", SIGGRAPH
// Asia, equation 12 with gamma = 1): x^(k+1) = omega_{k+1} (x~^(k+1) - x^(k-1)) + x^(k-1), where
// x~^(k+1) is the plain iteration's result and rho the estimate of its spectral radius.
// Projective Dynamics and Vertex Block Descent share it.

namespace drape {

/// The weight omega_k of iteration k (1-based): omega_1 = 1, omega_2 = 2 / (2 - rho^2),
/// omega_{k+1} = 4 / (4 - rho^2 omega_k); `previous` is omega_{k-1}.
inline double chebyshev_omega(int k, double rho, double previous) {
  const double rho2 = rho * rho;
  if (k <= 1) return 1.0;
  if (k == 2) return 2.0 / (2.0 - rho2);
  return 4.0 / (4.0 - rho2 * previous);
}

}  // namespace drape
