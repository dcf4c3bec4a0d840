#include "core/dummy/smooth_surface.hpp"

#include <algorithm>
#include <cmath>

namespace drape {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// One term of the gap with its derivatives.
struct GapTerm {
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
  Mat3 hessian = Mat3::Zero();
};

// max(a, b) + w/6 z^3 with z = 1 - |a - b|/w (Quilez's cubic smooth minimum, mirrored): equal
// to the maximum when |a - b| >= w, C2 everywhere (the correction's value, slope and curvature
// vanish at |a - b| = w; its odd part cancels the kink of max at a = b), never below max.
GapTerm smooth_max(const GapTerm& a, const GapTerm& b, double w) {
  const double d = a.value - b.value;
  if (d >= w) return a;
  if (d <= -w) return b;
  const double z = 1.0 - std::abs(d) / w;
  const double alpha = d >= 0.0 ? 1.0 - 0.5 * z * z : 0.5 * z * z;  // d smax / d a
  const Vec3 dg = a.gradient - b.gradient;
  GapTerm out;
  out.value = std::max(a.value, b.value) + w / 6.0 * z * z * z;
  out.gradient = alpha * a.gradient + (1.0 - alpha) * b.gradient;
  out.hessian = alpha * a.hessian + (1.0 - alpha) * b.hessian + (z / w) * dg * dg.transpose();
  return out;
}

// min(a, b) rounded the same way: -smax(-a, -b).
GapTerm smooth_min(const GapTerm& a, const GapTerm& b, double w) {
  const GapTerm m = smooth_max({-a.value, -a.gradient, -a.hessian}, {-b.value, -b.gradient, -b.hessian}, w);
  return {-m.value, -m.gradient, -m.hessian};
}

// The paraboloid's first-order distance f / |grad f|, f = side (y - apex) + r^2 / (2 rho) with r
// the horizontal distance from the cap's axis: |grad f| = sqrt(1 + r^2 / rho^2) depends on r
// only, so the quotient is a smooth function of the point.
GapTerm cap_gap(const SmoothSurface::DomeCap& c, const Vec3& p) {
  const Vec3 u(p.x() - c.cx, 0.0, p.z() - c.cz);
  const double q = u.squaredNorm(), rho2 = c.rho * c.rho;
  const double f = c.side * (p.y() - c.apex) + q / (2.0 * c.rho);
  const Vec3 grad_f = u / c.rho + c.side * Vec3::UnitY();
  Mat3 hess_f = Mat3::Zero();
  hess_f(0, 0) = hess_f(2, 2) = 1.0 / c.rho;
  const double S = 1.0 / std::sqrt(1.0 + q / rho2), S3 = S * S * S;
  const Vec3 grad_S = -S3 / rho2 * u;
  Mat3 hess_S = (3.0 * S3 * S * S / (rho2 * rho2)) * u * u.transpose();
  hess_S(0, 0) -= S3 / rho2;
  hess_S(2, 2) -= S3 / rho2;
  return {f * S, S * grad_f + f * grad_S,
          S * hess_f + grad_f * grad_S.transpose() + grad_S * grad_f.transpose() + f * hess_S};
}

}  // namespace

SmoothSurface::SmoothSurface(const DummySections& s) {
  build(s);
  // An end whose sections lean flatter than kDomeSlope is a dome (a sphere's pole, a head): the
  // slope-scaled radial gap there is far below the distance away from the surface (it is the
  // distance to the tangent plane at the same height), which would put an invisible shelf of
  // width about P delta around the pole. Such an end is cut at the first section steep enough
  // and closed by a paraboloid cap instead of the end plane.
  const int n = s.num_sections();
  int top = 0, bottom = n - 1;
  while (bottom - top > 3 && m_profile(top, 3) > kDomeSlope) ++top;
  while (bottom - top > 3 && m_profile(bottom, 3) > kDomeSlope) --bottom;
  if (top == 0 && bottom == n - 1) return;
  DummySections trimmed;
  trimmed.y.assign(s.y.begin() + top, s.y.begin() + bottom + 1);
  trimmed.cx.assign(s.cx.begin() + top, s.cx.begin() + bottom + 1);
  trimmed.cz.assign(s.cz.begin() + top, s.cz.begin() + bottom + 1);
  trimmed.radius = s.radius.middleRows(top, bottom - top + 1);
  build(trimmed);
  if (top > 0) m_caps[0] = dome_cap(0);
  if (bottom < n - 1) m_caps[1] = dome_cap(bottom - top);
}

// The paraboloid of revolution about the end section's centre through its mean radius Rm with
// the stack's mean slope P = |dRm/dy| there (curvature radius rho = Rm P at the ring, apex
// Rm / (2 P) beyond the end section). P is taken at least 1, so that the cap rises at most
// half its ring radius.
SmoothSurface::DomeCap SmoothSurface::dome_cap(int k) const {
  const detail::SplinePoint mean = along_height(locate(m_y[k]), m_profile, m_profile_yy, 2);
  const double slope = std::max(std::abs(mean.d1), 1.0);
  DomeCap cap;
  cap.dome = true;
  cap.side = k == 0 ? 1.0 : -1.0;
  cap.rho = m_profile(k, 2) * slope;
  cap.apex = m_y[k] + cap.side * m_profile(k, 2) / (2.0 * slope);
  cap.cx = m_profile(k, 0);
  cap.cz = m_profile(k, 1);
  return cap;
}

void SmoothSurface::build(const DummySections& s) {
  m_y = s.y;
  m_radius = s.radius;
  const int n = s.num_sections(), m = s.points();
  m_h_theta = kTwoPi / m;
  m_sections_per_metre = (n - 1) / (m_y.front() - m_y.back());
  // The edges between the sides and the end planes are rounded over half a mean section spacing.
  m_width = 0.5 / m_sections_per_metre;
  // Half the smallest radius keeps the axis treatment well inside the body; a stack with a zero
  // radius gets a tiny one instead (its surface touches the axis there anyway).
  m_axis_radius = std::max(0.5 * m_radius.minCoeff(), 1e-6);
  m_radius_yy = detail::natural_spline_moments(m_y, m_radius);
  m_angle = detail::periodic_spline_moments(m_radius);
  m_angle_yy = detail::natural_spline_moments(m_y, m_angle);
  m_profile.resize(n, 4);
  for (int k = 0; k < n; ++k) {
    m_profile(k, 0) = s.cx[k];
    m_profile(k, 1) = s.cz[k];
    m_profile(k, 2) = m_radius.row(k).mean();
  }
  // The slope scale's knots: the RMS over angles of the radius' height slope at each section.
  m_profile.col(3).setZero();
  for (int k = 0; k < n; ++k) {
    const HeightPoint hp = locate(m_y[k]);
    double sum = 0.0;
    for (int j = 0; j < m; ++j) {
      const double slope = along_height(hp, m_radius, m_radius_yy, j).d1;
      sum += slope * slope;
    }
    m_profile(k, 3) = std::sqrt(sum / m);
  }
  m_profile_yy = detail::natural_spline_moments(m_y, m_profile);
}

SmoothSurface::HeightPoint SmoothSurface::locate(double y) const {
  const int last = static_cast<int>(m_y.size()) - 2;
  HeightPoint hp;
  if (y >= m_y.front()) {
    hp.k = 0, hp.f = 0.0, hp.excess = m_y.front() - y;
  } else if (y <= m_y.back()) {
    hp.k = last, hp.f = 1.0, hp.excess = m_y.back() - y;
  } else {
    int k = static_cast<int>((m_y.front() - y) * m_sections_per_metre);
    k = std::clamp(k, 0, last);
    while (k > 0 && y > m_y[k]) --k;
    while (k < last && y < m_y[k + 1]) ++k;
    hp.k = k;
    hp.f = (m_y[k] - y) / (m_y[k] - m_y[k + 1]);
  }
  hp.h = m_y[hp.k] - m_y[hp.k + 1];
  return hp;
}

// The spline's parameter runs downwards (u = y_k - y), so d/dy = -d/du; beyond the end knots
// it continues along its tangent (the natural spline's curvature is 0 there: a C2 join).
detail::SplinePoint SmoothSurface::along_height(const HeightPoint& hp,
                                                const Eigen::MatrixXd& values,
                                                const Eigen::MatrixXd& moments, int col) const {
  const int k = hp.k;
  detail::SplinePoint p = detail::cubic_segment(values(k, col), values(k + 1, col),
                                                moments(k, col), moments(k + 1, col), hp.h, hp.f);
  if (hp.excess != 0.0) p.value += p.d1 * hp.excess, p.d2 = 0.0;
  p.d1 = -p.d1;
  return p;
}

SmoothSurface::RadiusPoint SmoothSurface::radius_at(const HeightPoint& hp, double theta) const {
  const int m = static_cast<int>(m_radius.cols());
  double u = theta / m_h_theta;
  u -= m * std::floor(u / m);
  int j = static_cast<int>(u);
  if (j >= m) j = m - 1;
  const int j1 = j + 1 == m ? 0 : j + 1;
  const double f = u - j;
  const detail::SplinePoint a = along_height(hp, m_radius, m_radius_yy, j);
  const detail::SplinePoint b = along_height(hp, m_radius, m_radius_yy, j1);
  const detail::SplinePoint ma = along_height(hp, m_angle, m_angle_yy, j);
  const detail::SplinePoint mb = along_height(hp, m_angle, m_angle_yy, j1);
  // The angle spline is linear in its data, so its height derivatives are the same spline
  // through the data's height derivatives (a tensor-product bicubic: C2 in both variables).
  const detail::SplinePoint d0 = detail::cubic_segment(a.value, b.value, ma.value, mb.value, m_h_theta, f);
  const detail::SplinePoint d1 = detail::cubic_segment(a.d1, b.d1, ma.d1, mb.d1, m_h_theta, f);
  const detail::SplinePoint d2 = detail::cubic_segment(a.d2, b.d2, ma.d2, mb.d2, m_h_theta, f);
  return {d0.value, d0.d1, d0.d2, d1.value, d1.d1, d2.value};
}

double SmoothSurface::radius(double y, double theta) const { return radius_at(locate(y), theta).r; }

Eigen::Vector2d SmoothSurface::axis(double y) const {
  const HeightPoint hp = locate(y);
  return {along_height(hp, m_profile, m_profile_yy, 0).value,
          along_height(hp, m_profile, m_profile_yy, 1).value};
}

SmoothGap SmoothSurface::gap(const Vec3& p) const {
  const HeightPoint hp = locate(p.y());
  const detail::SplinePoint cx = along_height(hp, m_profile, m_profile_yy, 0);
  const detail::SplinePoint cz = along_height(hp, m_profile, m_profile_yy, 1);
  const detail::SplinePoint mean = along_height(hp, m_profile, m_profile_yy, 2);
  const detail::SplinePoint slope = along_height(hp, m_profile, m_profile_yy, 3);
  // The side gap in q = (hx, y, hz), hx = x - cx(y), hz = z - cz(y).
  const double hx = p.x() - cx.value, hz = p.z() - cz.value;
  const double r = std::hypot(hx, hz);
  const double r1 = m_axis_radius, b = 0.5 * r1;
  // r~: r outside r1; inside, 3 r1/8 + 3 r^2/(4 r1) - r^4/(8 r1^3), which meets r with its
  // first two derivatives at r1 and is a polynomial in hx^2 + hz^2 (smooth on the axis).
  const double c2 = 3.0 / (4.0 * r1), c4 = -1.0 / (8.0 * r1 * r1 * r1);
  GapTerm side;
  Vec3& gq = side.gradient;
  Mat3& hq = side.hessian;
  if (r < b) {
    // Only the angular mean of the radius this near the axis: no angle at all.
    const double slope_r2 = 2.0 * c2 + 4.0 * c4 * r * r;  // d r~ / d(hx), divided by hx
    side.value = 3.0 * r1 / 8.0 + c2 * r * r + c4 * r * r * r * r - mean.value;
    gq = Vec3(slope_r2 * hx, -mean.d1, slope_r2 * hz);
    hq(0, 0) = slope_r2 + 8.0 * c4 * hx * hx;
    hq(2, 2) = slope_r2 + 8.0 * c4 * hz * hz;
    hq(0, 2) = hq(2, 0) = 8.0 * c4 * hx * hz;
    hq(1, 1) = -mean.d2;
  } else {
    double rt = r, rt1 = 1.0, rt2 = 0.0;
    if (r < r1) rt = 3.0 * r1 / 8.0 + c2 * r * r + c4 * r * r * r * r,
                rt1 = 2.0 * c2 * r + 4.0 * c4 * r * r * r, rt2 = 2.0 * c2 + 12.0 * c4 * r * r;
    // chi fades the angular part in between b and r1 (a quintic smoothstep, C2).
    double chi = 1.0, chi1 = 0.0, chi2 = 0.0;
    if (r < r1) {
      const double s = (r - b) / b;
      chi = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
      chi1 = 30.0 * s * s * (1.0 - s) * (1.0 - s) / b;
      chi2 = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) / (b * b);
    }
    const RadiusPoint R = radius_at(hp, std::atan2(hx, hz));
    const double dev = R.r - mean.value, dev_y = R.r_y - mean.d1, dev_yy = R.r_yy - mean.d2;
    // g(r, theta, y) = r~(r) - mean(y) - chi(r) (R(y, theta) - mean(y)) and its derivatives.
    const double g_r = rt1 - chi1 * dev, g_t = -chi * R.r_t, g_y = -mean.d1 - chi * dev_y;
    const double g_rr = rt2 - chi2 * dev, g_rt = -chi1 * R.r_t, g_ry = -chi1 * dev_y;
    const double g_tt = -chi * R.r_tt, g_ty = -chi * R.r_yt, g_yy = -mean.d2 - chi * dev_yy;
    side.value = rt - mean.value - chi * dev;
    // To (hx, hz): grad r = rho, grad theta = tau / r, Hess r = tau tau^T / r,
    // Hess theta = -(rho tau^T + tau rho^T) / r^2.
    const Eigen::Vector2d rho(hx / r, hz / r), tau(hz / r, -hx / r);
    const Eigen::Vector2d grad_h = g_r * rho + (g_t / r) * tau;
    const Eigen::Matrix2d sym = rho * tau.transpose() + tau * rho.transpose();
    const Eigen::Matrix2d hess_h = g_rr * rho * rho.transpose() + (g_rt / r - g_t / (r * r)) * sym +
                                   (g_tt / (r * r) + g_r / r) * tau * tau.transpose();
    const Eigen::Vector2d cross = g_ry * rho + (g_ty / r) * tau;
    gq = Vec3(grad_h.x(), g_y, grad_h.y());
    hq << hess_h(0, 0), cross.x(), hess_h(0, 1),  //
        cross.x(), g_yy, cross.y(),               //
        hess_h(1, 0), cross.y(), hess_h(1, 1);
  }
  // The slope scale s = (1 + P^2)^(-1/2) makes the side gap about a distance where the surface
  // leans (on a sphere near its poles the radial gap is many times the distance).
  const double P = slope.value, P1 = slope.d1, P2 = slope.d2, q = 1.0 + P * P;
  const double s = 1.0 / std::sqrt(q), s1 = -P * P1 * s / q,
               s2 = -(P1 * P1 + P * P2) * s / q + 3.0 * P * P * P1 * P1 * s / (q * q);
  const Vec3 ey = Vec3::UnitY();
  hq = s * hq + s1 * (gq * ey.transpose() + ey * gq.transpose()) + side.value * s2 * ey * ey.transpose();
  gq = s * gq + side.value * s1 * ey;
  side.value *= s;
  // From q to p: dq/dp = I - [cx', 0, cz'] e_y^T, and the axis' curvature adds to d2/dy2.
  Mat3 J = Mat3::Identity();
  J(0, 1) = -cx.d1;
  J(2, 1) = -cz.d1;
  const double axis_curvature = -gq.x() * cx.d2 - gq.z() * cz.d2;
  side.hessian = J.transpose() * hq * J;
  side.hessian(1, 1) += axis_curvature;
  side.gradient = J.transpose() * gq;

  GapTerm top{p.y() - m_y.front(), ey, Mat3::Zero()};
  GapTerm bottom{m_y.back() - p.y(), -ey, Mat3::Zero()};
  // A dome end: the union of the paraboloid's body and the half-space below the end plane.
  if (m_caps[0].dome) top = smooth_min(cap_gap(m_caps[0], p), top, m_width);
  if (m_caps[1].dome) bottom = smooth_min(cap_gap(m_caps[1], p), bottom, m_width);
  const GapTerm closed = smooth_max(smooth_max(side, top, m_width), bottom, m_width);
  return {closed.value, closed.gradient, closed.hessian};
}

}  // namespace drape
