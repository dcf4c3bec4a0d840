#pragma once
// The seeded perturbation of a run's initial state (docs/scene.md `perturbation`;
// docs/experiments.md, "Ensembles"): the repeats of an ensemble differ only by it; its stretch
// and velocity give hard starts.
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
/// A hard start (docs/scene.md `perturbation.stretch`): every position of y, fixed particles
/// included, scaled by 1 + stretch about the centroid of the fixed particles (of all particles
/// when none is fixed), and each fixed particle fixed again where it moved to. Every spring
/// then starts 1 + stretch times as long as in y; a single pin stays where it is. Call it while
/// only pins are fixed (they are fixed points).
void stretch_initial_positions(double stretch, ConstraintSet& constraints, Eigen::VectorXd& y);
/// Gives every free particle of y a velocity of perturbation.velocity per coordinate (uniform in
/// [-1, 1] or standard normal, from a stream of the seed no position perturbation uses);
/// fixed particles and positions stay. Nothing changes when p.velocity is 0.
void perturb_initial_velocities(const Perturbation& p, const ConstraintSet& constraints,
                                Eigen::VectorXd& y);
/// The whole initial perturbation of a run, in this order: stretch, positions, velocities.
void perturb_initial_state(const Perturbation& p, double spacing, ConstraintSet& constraints,
                           Eigen::VectorXd& y);

}  // namespace drape
