#pragma once
// The seeded perturbation of a run's initial positions (docs/scene.md `perturbation`;
// docs/experiments.md, "Ensembles"): the repeats of an ensemble differ only by it.
#include <Eigen/Core>
#include <cstdint>

#include "core/model/constraints.hpp"
#include "core/scene/scene.hpp"

namespace drape {

/// Moves every free particle of y = [x; v] by a * spacing per coordinate (uniform in [-1, 1] or
/// standard normal, from a generator seeded with p.seed); fixed particles and velocities stay.
/// Nothing changes when p.position is 0.
void perturb_initial_positions(const Perturbation& p, double spacing,
                               const ConstraintSet& constraints, Eigen::VectorXd& y);
/// The same from stream `stream` of the seed (0: the initial perturbation; k: after the k-th
/// map, perturbation.after_map), each stream its own sequence.
void perturb_positions(const Perturbation& p, std::uint64_t stream, double spacing,
                       const ConstraintSet& constraints, Eigen::VectorXd& y);

}  // namespace drape
