#include "experiments/run/divergence_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace drape {

void DivergenceCheck::account_for(const ClothSystem& system, const EnergyBreakdown& e) {
  const double stored = std::max(0.0, e.kinetic + e.spring + e.collision);
  m_stored_speed = std::max(m_stored_speed, std::sqrt(2.0 * stored / system.particle_mass()));
}

std::string DivergenceCheck::reason(const ClothSystem& system, double t,
                                    const Eigen::VectorXd& y) const {
  if (!y.allFinite()) return "non-finite state";
  const Eigen::Index n = system.num_particles();
  const auto v = y.tail(3 * n);
  double max_speed2 = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    max_speed2 = std::max(max_speed2, v.segment<3>(3 * i).squaredNorm());
  const double limit = m_base + m_stored_speed + 2.0 * system.constraints().max_speed(t);
  if (max_speed2 > limit * limit)
    return fmt::format("runaway: a particle moves at {:.3g} m/s, above the bound {:.3g} m/s",
                       std::sqrt(max_speed2), limit);
  return {};
}

EnergyBreakdown energy_of(const ClothSystem& system, const Eigen::VectorXd& y) {
  const Eigen::Index n3 = 3 * system.num_particles();
  return system.energy(ConstVecMap(y.data(), n3), ConstVecMap(y.data() + n3, n3));
}

}  // namespace drape
