#pragma once
// The smooth dummy surface of the `smooth` collision model (docs/model.md section 4.11): a C2
// gap function G(p) whose zero set is the dummy's surface, with its gradient and Hessian, for
// contact potentials that Newton's method can solve (the interpolated surface of section 3 has
// a gradient that jumps across sections and angle bins).
#include <Eigen/Core>
#include <vector>

#include "core/dummy/cubic_spline.hpp"
#include "core/dummy/dummy.hpp"

namespace drape {

/// The smooth gap at a point: value, gradient and Hessian (G < 0 inside the dummy).
struct SmoothGap {
  double gap = 0.0;
  Vec3 gradient = Vec3::Zero();
  Mat3 hessian = Mat3::Zero();
};

/// G(p) = smax(smax(s(y) g(p), y - y_top), y_bottom - y), with g = r~(r_h) - R(y, theta(p)) the
/// radial gap to the bicubic spline radius R (periodic in angle, natural across sections),
/// r_h measured from the spline axis c(y), s(y) = 1 / sqrt(1 + P(y)^2) a slope scale and smax
/// a C2 smooth maximum that closes the stack with its top and bottom planes. Near the axis
/// (r_h < axis_radius()) r~ turns into an even polynomial and the angular part of R fades out,
/// so that G stays C2 there too. A dome end (sections flatter than kDomeSlope, a sphere's pole)
/// is cut at the first steep enough section and its plane term becomes the smooth minimum of
/// that plane and a paraboloid cap's gap. Every coefficient is computed once, at construction.
class SmoothSurface {
 public:
  /// A dome end's paraboloid of revolution: side (y - apex) + r^2 / (2 rho) = 0, r the horizontal
  /// distance from (cx, cz); side = +1 at the top, -1 at the bottom.
  struct DomeCap {
    bool dome = false;
    double side = 1.0, apex = 0.0, rho = 1.0, cx = 0.0, cz = 0.0;
  };
  /// Ends whose sections lean flatter than this slope |dR/dy| (the sphere's poles) are domes.
  static constexpr double kDomeSlope = 3.0;

  explicit SmoothSurface(const DummySections& sections);

  /// G, grad G and the Hessian of G at p (C2 everywhere).
  SmoothGap gap(const Vec3& p) const;
  /// The spline radius R(y, theta) (linear continuation above the top and below the bottom).
  double radius(double y, double theta) const;
  /// The spline axis (cx, cz) at height y.
  Eigen::Vector2d axis(double y) const;
  /// Width of the smooth maximum that rounds the edges between the sides and the end planes.
  double blend_width() const { return m_width; }
  /// Below this horizontal distance from the axis the angle fades out of the gap.
  double axis_radius() const { return m_axis_radius; }

 private:
  struct HeightPoint {
    int k = 0;            // segment between sections k and k + 1
    double f = 0.0;       // weight of section k + 1
    double h = 1.0;       // y_k - y_{k+1}
    double excess = 0.0;  // beyond the end sections: distance past the end knot, along -y
  };
  /// R and its derivatives in y and theta.
  struct RadiusPoint {
    double r = 0.0, r_t = 0.0, r_tt = 0.0, r_y = 0.0, r_yt = 0.0, r_yy = 0.0;
  };
  void build(const DummySections& sections);
  DomeCap dome_cap(int k) const;
  HeightPoint locate(double y) const;
  /// The natural spline through column `col` of `values` at height point hp: derivatives in y.
  detail::SplinePoint along_height(const HeightPoint& hp, const Eigen::MatrixXd& values,
                                   const Eigen::MatrixXd& moments, int col) const;
  RadiusPoint radius_at(const HeightPoint& hp, double theta) const;

  std::vector<double> m_y;       // section heights, top first
  Eigen::MatrixXd m_radius;      // sections x points: the data radii
  Eigen::MatrixXd m_radius_yy;   // their moments in height
  Eigen::MatrixXd m_angle;       // moments in angle of each section's periodic spline
  Eigen::MatrixXd m_angle_yy;    // their moments in height
  Eigen::MatrixXd m_profile;     // sections x 4: cx, cz, mean radius, RMS radius slope
  Eigen::MatrixXd m_profile_yy;  // their moments in height
  double m_sections_per_metre = 0.0;
  double m_h_theta = 0.0;
  double m_width = 0.0;
  double m_axis_radius = 0.0;
  DomeCap m_caps[2];  // top, bottom
};

}  // namespace drape
