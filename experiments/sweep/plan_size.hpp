#pragma once
// The size of an experiment's plan, counted from its lists before anything is expanded: a sweep
// of 9 keys x 10 values is 10^9 runs, whose plan alone would exhaust memory (docs/experiments.md,
// Limits).
#include <cstdint>

#include "experiments/sweep/experiment.hpp"

namespace drape {

/// The most runs a plan may hold, reference runs included: each is a folder and a process.
constexpr std::int64_t max_plan_runs = 100'000;

/// scenes x cases x sweep x repeats, doubled with a reference (at most one each), in a double
/// so that no product overflows.
double plan_size_bound(const Experiment& experiment);
/// Throws InputError naming the experiment file and its largest factor (sweep, cases, repeats
/// or scenes) when plan_size_bound exceeds max_plan_runs.
void check_plan_size(const Experiment& experiment);

}  // namespace drape
