#pragma once
// The check of a plan before any run starts (docs/experiments.md, "Bad input"): every run's
// scene with its overrides is loaded and everything a run reads besides it is built once (the
// integrator's options and step limits, the dummy, the hand recording), so that bad input stops
// the experiment with exit 2 and no output folder, instead of a table of runs that "could not
// run". An error in a value the experiment gave names the experiment's field, not the scene.
#include <vector>

#include "experiments/sweep/experiment.hpp"

namespace drape {

/// Throws InputError for the first run of `runs` whose input is bad, naming the experiment (or
/// cases) file and field when an override of the experiment gave the bad value.
void validate_runs(const Experiment& experiment, const std::vector<RunSpec>& runs);

}  // namespace drape
