#pragma once
// The checks that need both the scene and its integrator options (docs/scene.md, Limits): a
// step that cannot advance time, or more steps than integrator.max_steps allows, is bad input
// found before anything is built, not a run that spins or fails late.
#include <string>

#include "core/scene/scene.hpp"
#include "integrators/interface/integrator_options.hpp"

namespace drape {

/// Throws InputError naming the scene file and integrator.dt or integrator.max_dt (under
/// `integrator_field`) when a step is too small to advance time over the duration or implies
/// more than max_steps steps.
void check_run_limits(const Scene& scene, const IntegratorOptions& options,
                      const std::string& integrator_field = "integrator");

}  // namespace drape
