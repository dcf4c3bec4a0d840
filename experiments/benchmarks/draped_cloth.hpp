#pragma once
// The draped-cloth setup that the benchmarks share: an n x n cloth wrapped around the built-in
// dress form, in contact everywhere.
#include <cmath>
#include <memory>

#include "core/model/cloth_system.hpp"
#include "core/dummy/dummy_sources.hpp"
#include "integrators/explicit/leapfrog.hpp"

namespace drape::bench {

inline constexpr double pi = 3.14159265358979323846;

/// The built-in dress form, built once.
inline const std::shared_ptr<const Dummy>& dress_form() {
  static const auto dummy = std::make_shared<const Dummy>(
      make_dummy(nlohmann::json{{"builtin", "dress-form"}}, "bench", "dummy", "."));
  return dummy;
}

/// An n x n cloth wrapped around the dress form from the shoulders down, every particle half a
/// threshold outside the surface: a state where most collision queries find contact (79 % of
/// the particles at 64 x 64 are within the threshold of an object particle; the others lie
/// between object particles, which are 3 cm apart round the body). Not a force balance: for
/// timing force evaluations, and the start of the integrator benchmarks.
inline std::unique_ptr<ClothSystem> draped_cloth(int n, Eigen::VectorXd& y, bool with_dummy = true,
                                                 CollisionModel model = CollisionModel::particle) {
  const Dummy& dummy = *dress_form();
  ClothParams p;
  p.rows = p.cols = n;
  p.spacing = 0.5 / n;
  p.particle_mass = 0.2 / (n * n);
  p.k_structural = 50.0;
  p.k_shear = 50.0;
  p.damping_spring = 0.01;
  p.damping_air = 0.001;
  p.origin = Vec3(0.0, 1.3, 0.2);
  ForceParams forces;
  forces.collision = {0.01, 1000.0, model};
  auto system = std::make_unique<ClothSystem>(build_cloth(p), with_dummy ? dress_form() : nullptr, forces);
  y = Eigen::VectorXd::Zero(system->size());
  const double y_top = dummy.sections().y.front() - 0.02;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const double height = y_top - r * p.spacing;
      const double theta = 2.0 * pi * (c - n / 2) / n * 0.45;  // the front 160 degrees
      const Eigen::Vector2d axis = dummy.axis_at(height);
      const double radius = dummy.surface_radius(height, theta) + 0.5 * forces.collision.threshold;
      y.segment<3>(3 * (r * n + c)) =
          Vec3(axis.x() + radius * std::sin(theta), height, axis.y() + radius * std::cos(theta));
    }
  return system;
}

/// Fraction of the cloth particles of y within the collision threshold of an object particle.
inline double contact_fraction(const ClothSystem& system, const Eigen::VectorXd& y) {
  int in_contact = 0;
  for (int i = 0; i < system.num_particles(); ++i)
    if (system.dummy()->nearest_within(y.segment<3>(3 * i), system.params().collision.threshold)
            .index >= 0)
      ++in_contact;
  return static_cast<double>(in_contact) / system.num_particles();
}

/// A garment worn tight: draped_cloth's placement with rest lengths 15 % shorter (so the cloth
/// is stretched over the front of the dress form), its top row and side columns pinned, and
/// settled by `settle_time` of leap-frog with strong air damping (a decay time of 20 ms).
/// draped_cloth itself starts half a threshold deep in the collision shell, far from the force
/// balance: left to itself it leaves the dress form within 0.2 s.
inline std::unique_ptr<ClothSystem> settled_drape(int n, Eigen::VectorXd& y,
                                                  double settle_time = 0.3) {
  const auto wrapped = draped_cloth(n, y);
  const ClothParams placed = wrapped->cloth().params;
  const auto build = [&](double damping_air) {
    ClothParams p = placed;
    p.spacing *= 0.85;
    p.damping_air = damping_air;
    auto system = std::make_unique<ClothSystem>(build_cloth(p), dress_form(), wrapped->params());
    for (int k = 0; k < n; ++k)
      for (const int i : {k, k * n, k * n + n - 1})
        system->constraints().fix_at(i, y.segment<3>(3 * i));
    return system;
  };
  auto settling = build(placed.particle_mass / 0.02);
  Leapfrog leapfrog(*settling, 1e-4);
  leapfrog.reset(0.0, y);
  while (leapfrog.time() < settle_time - 1e-12) leapfrog.step(settle_time);
  y = leapfrog.state();
  return build(placed.damping_air);
}

}  // namespace drape::bench
