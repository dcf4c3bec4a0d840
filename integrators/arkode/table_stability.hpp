#pragma once
// Linear, internal and nonlinear stability measures of a diagonally implicit Butcher tableau,
// to compare the ARKODE tables that gain energy on the stiff swinging sheet at 1/30 s with those
// that settle (docs/findings/energy_gaining_tables.md, "Which tables gain energy at large steps").
#include <complex>
#include <vector>

#include "integrators/arkode/butcher_tableau.hpp"

namespace drape {

/// The stability measures of one tableau.
struct TableStability {
  double min_weight = 0.0;  ///< min_i b_i
  /// Smallest eigenvalue of M = B A + A^T B - b b^T: with min_weight >= 0, >= 0 means
  /// algebraically stable (Burrage and Butcher 1979).
  double algebraic_stability = 0.0;
  double max_imaginary_axis = 0.0;  ///< max over y of |R(iy)| (sampled, see .cpp)
  double stiff_limit = 0.0;         ///< |R(-inf)|
  std::vector<double> stage_max_imaginary_axis;  ///< per stage, max over y of |R_int_i(iy)|
  std::vector<double> stage_stiff_limit;         ///< per stage, |R_int_i(-inf)|
  double max_coefficient = 0.0;                  ///< max |a_ij|
  bool nodes_in_unit_interval = true;            ///< every c_i in [0, 1]
  /// Infinity norm of the inverse of A restricted to its implicit stages (a_ii != 0).
  double implicit_inverse_norm = 0.0;
};

/// R(z) = 1 + z b^T (I - z A)^-1 1, the linear stability function.
std::complex<double> stability_function(const ButcherTableau& tableau, std::complex<double> z);
/// R_int(z) = 1 + z A (I - z A)^-1 1: stage i's value for y' = lambda y, y0 = 1, z = h lambda
/// (Kennedy and Carpenter 2016, NASA/TM-2016-219173, "internal stability").
std::vector<std::complex<double>> stage_stability_functions(const ButcherTableau& tableau,
                                                            std::complex<double> z);
/// Every measure of TableStability for `tableau`.
TableStability table_stability(const ButcherTableau& tableau);

}  // namespace drape
