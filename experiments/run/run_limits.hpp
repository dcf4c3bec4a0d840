#pragma once
// The checks that need both the scene and its integrator options (docs/scene.md, Limits): a
// step that cannot advance time, or more steps than integrator.max_steps allows, is bad input
// found before anything is built, not a run that spins or fails late.
#include <string>

#include "core/input/hand_track.hpp"
#include "core/scene/scene.hpp"
#include "integrators/interface/integrator_options.hpp"

namespace drape {

/// Throws InputError naming the scene file and integrator.dt or integrator.max_dt (under
/// `integrator_field`) when a step is too small to advance time over the duration or implies
/// more than max_steps steps.
void check_run_limits(const Scene& scene, const IntegratorOptions& options,
                      const std::string& integrator_field = "integrator");

/// Throws InputError naming the scene file and integrator.linear_solver when sparse-direct's
/// factorisation of the scene's cloth would need more than `available_bytes` (the measured
/// growth, run_limits.cpp); check_run_limits passes the machine's physical memory.
void check_linear_solver_memory(const Scene& scene, const IntegratorOptions& options,
                                const std::string& integrator_field, double available_bytes);

/// The most frames that events can add to trace.csv, frames/ and event_trace/ (a frame at each
/// step that ends on an event) for a run driven by `track` (docs/outputs.md, "Event frames").
double event_frames_bound(const HandTrack& track);

/// Throws InputError naming the scene file and the output field when a file could get more rows
/// than limits::max_output_rows: energy.csv and hands.csv at `energy_interval: 0` (a row every
/// step, up to max_steps or duration / dt), and the frame files at their intervals plus
/// `event_frames` frames at events (parse_scene checks the intervals alone).
void check_output_rows(const Scene& scene, const IntegratorOptions& options, double event_frames);

}  // namespace drape
