#pragma once
// C2 cubic splines in moment form (the second derivative at each knot), the building blocks of
// the smooth dummy surface (docs/model.md section 4.11): natural splines in height across the
// sections, periodic splines in angle round each section.
#include <Eigen/Core>
#include <vector>

namespace drape::detail {

/// Value and first two derivatives of a spline at a point, with respect to its parameter.
struct SplinePoint {
  double value = 0.0;
  double d1 = 0.0;
  double d2 = 0.0;
};

/// The cubic between knots a (f = 0) and b (f = 1), h apart, with second derivatives Ma, Mb
/// there: derivatives with respect to u = f h.
inline SplinePoint cubic_segment(double a, double b, double Ma, double Mb, double h, double f) {
  const double e = 1.0 - f;
  return {e * a + f * b + h * h / 6.0 * ((e * e * e - e) * Ma + (f * f * f - f) * Mb),
          (b - a) / h + h / 6.0 * (-(3.0 * e * e - 1.0) * Ma + (3.0 * f * f - 1.0) * Mb),
          e * Ma + f * Mb};
}

/// Second derivatives (moments) of the natural cubic splines through each column of `values`
/// at the strictly monotone knots (one row per knot): zero at the end knots, so the splines
/// continue linearly beyond them with C2 joins.
Eigen::MatrixXd natural_spline_moments(const std::vector<double>& knots,
                                       const Eigen::MatrixXd& values);

/// Moments of the periodic cubic splines through each row of `values`, its columns at evenly
/// spaced angles 2 pi j / columns (one full turn).
Eigen::MatrixXd periodic_spline_moments(const Eigen::MatrixXd& values);

}  // namespace drape::detail
