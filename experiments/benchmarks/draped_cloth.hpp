#pragma once
// The draped-cloth setup that the benchmarks share: an n x n cloth wrapped around the built-in
// dress form, in contact everywhere.
#include <cmath>
#include <memory>

#include "core/cloth_system.hpp"
#include "core/dummy_sources.hpp"

namespace drape::bench {

inline constexpr double pi = 3.14159265358979323846;

/// The built-in dress form, built once.
inline const std::shared_ptr<const Dummy>& dress_form() {
  static const auto dummy = std::make_shared<const Dummy>(
      make_dummy(nlohmann::json{{"builtin", "dress-form"}}, "bench", "dummy", "."));
  return dummy;
}

/// An n x n cloth wrapped around the dress form from the shoulders down, every particle half a
/// threshold outside the surface: the draped state, where every collision query finds contact.
inline std::unique_ptr<ClothSystem> draped_cloth(int n, Eigen::VectorXd& y,
                                                 bool with_dummy = true) {
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
  forces.collision = {0.01, 1000.0};
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

}  // namespace drape::bench
