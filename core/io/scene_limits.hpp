#pragma once
// The bounds every scene value is checked against before anything is built (docs/scene.md,
// Limits). They are physically generous: no draping scene comes near them, and below them no
// product the model forms (k * length, m * g * height, rows * cols, duration / dt) overflows a
// double or a 64-bit count, so a run either works or ends `diverged` with its summary.
#include <cstddef>
#include <cstdint>

namespace drape::limits {

/// Cloth particles, rows x cols (computed in 64 bits): 4 million, about 1 GB of state and springs.
constexpr std::int64_t max_cloth_particles = 4'000'000;
/// Lengths: cloth spacing, collision threshold, hold threshold, dummy radius [m].
constexpr double max_length = 1e3;
/// cloth.spacing [m]: at least a micrometre, and at least 2^-30 of the cloth origin's largest
/// coordinate, so that neighbouring particles' coordinates differ in many more than their last
/// digits (at 1e-17 m every particle started at one point, and the stability estimate's
/// eigensolver failed).
constexpr double min_spacing = 1e-6;
constexpr double min_spacing_of_origin = 0x1p-30;
/// Coordinates of positions given in a scene (cloth origin, map_top, dummy heights) [m].
constexpr double max_coordinate = 1e6;
/// Hand positions as a recording holds them, in the sensor frame [sensor units]: the transform
/// (scale up to 1000) maps them to the scene, where a hand must be within 10 m of the origin
/// (max_hand_coordinate, core/input/hand_track.hpp); this bounds what `drapelab convert` copies.
constexpr double max_sensor_coordinate = 1e6;
/// Times of a recording or inline event, and input.time_offset [s]: within +-10^10 s, about 300
/// years, so that Unix timestamps pass and the scene times offset + scale t stay exact enough.
constexpr double max_recording_time = 1e10;
/// input.time_scale lies in [1 / max_time_scale, max_time_scale]: a smaller scale would map a
/// whole recording onto one instant of the scene.
constexpr double max_time_scale = 1e3;
/// Spring and collision stiffness [N/m] and damping coefficients [N s/m].
constexpr double max_stiffness = 1e12;
/// Particle mass [kg]: at most 10^6 and at least a picogram, so that k / m and c / m stay below
/// 10^24 /s^2 and /s (a mass of 1e-300 with k = 1e12 gave an infinite frequency).
constexpr double max_mass = 1e6;
constexpr double min_mass = 1e-12;
/// collision.friction: Coulomb coefficients of real fabrics on a dress form are below 1; 10 is
/// far beyond any and keeps mu lambda finite.
constexpr double max_friction = 10.0;
/// collision.friction_epsilon [m/s]: the mollifier's width 1 / epsilon_v h enters the friction
/// Hessian, so a micrometre per second bounds it (2 / (1e-9 * 1e-6) stays far from overflow);
/// beyond 100 m/s no draping motion reaches Coulomb's bound.
constexpr double min_friction_epsilon = 1e-9;
constexpr double max_friction_epsilon = 100.0;
/// Length of the gravity vector [m/s^2].
constexpr double max_gravity = 1e3;
/// Simulated time [s].
constexpr double max_duration = 1e6;
/// perturbation.position, a fraction of cloth.spacing: past half a spacing two uniformly
/// perturbed neighbours can pass each other, so the run would start from a tangled cloth, not
/// from a perturbed one (an ensemble's default is 1e-3).
constexpr double max_perturbation = 0.5;
/// perturbation.stretch, a fraction of every spring's rest length: at -1 every particle starts
/// at one point; beyond half, either way, the start is no longer a stretched or compressed cloth
/// but a tangle or a cloth twice its size.
constexpr double max_stretch = 0.5;
/// perturbation.velocity [m/s]: ten times the runaway bound's own 10 m/s (docs/outputs.md); no
/// hard start of a draping cloth is faster.
constexpr double max_velocity_perturbation = 100.0;
/// Horizons of restart_error: each one reruns the scene's method after every event.
constexpr std::size_t max_restart_horizons = 16;
/// Rows of an output file implied by an interval: rows per frame x frames (trace.csv, frames/),
/// or frames (energy.csv, hands.csv).
constexpr double max_output_rows = 1e9;
/// A step or an interval shorter than duration x this cannot advance time near the end of the
/// run (t + dt == t once dt < t 2^-53): refused as input instead of looping for ever.
constexpr double min_relative_step = 0x1p-50;
/// integrator.max_steps.
constexpr std::int64_t max_steps = 1'000'000'000'000;

}  // namespace drape::limits
