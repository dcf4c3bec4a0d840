#include "experiments/run/run_limits.hpp"

#include <unistd.h>

#include <cmath>

#include <fmt/format.h>

#include "core/io/input_error.hpp"
#include "core/io/scene_limits.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/linear/reduced_newton_solver.hpp"

namespace drape {

namespace {

void check_advances(const Scene& scene, const std::string& field, double step) {
  // Near the end t + step == t once step < duration 2^-53; 2^-50 leaves room for round-off.
  if (step > 0.0 && step < scene.duration * limits::min_relative_step)
    throw InputError(scene.file, field,
                     "too small to advance time over duration " +
                         nlohmann::json(scene.duration).dump() + " s (at least duration x 2^-50)");
}

// The sparse LDLT of S (linear_solver sparse-direct) on an n-particle grid, peak resident
// memory of a one-step run: 129 MB at 128 x 128, 512 MB at 256 x 256, 2.42 GB at 512 x 512
// (/usr/bin/time, docs/scene.md "Limits"); the growth per fourfold grid rose from n^0.99 to
// n^1.12, so beyond 512 x 512 it is taken as n^1.25, above what was measured.
constexpr int measured_side = 512;
constexpr double measured_bytes = 2.42e9;

double sparse_direct_bytes(double particles) {
  const double ratio = particles / (double{measured_side} * measured_side);
  return measured_bytes * (ratio <= 1.0 ? ratio : std::pow(ratio, 1.25));
}

double physical_memory_bytes() {
  return static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
         static_cast<double>(::sysconf(_SC_PAGE_SIZE));
}

}  // namespace

void check_linear_solver_memory(const Scene& scene, const IntegratorOptions& options,
                                const std::string& integrator_field, double available_bytes) {
  if (reduced_solve_named(linear_solver_of(options)) != ReducedSolve::sparse_ldlt) return;
  const double particles =
      static_cast<double>(scene.cloth.rows) * static_cast<double>(scene.cloth.cols);
  const double needed = sparse_direct_bytes(particles);
  if (needed > available_bytes)
    throw InputError(scene.file, integrator_field + ".linear_solver",
                     fmt::format("sparse-direct for a {} x {} cloth needs about {:.3g} GB (its "
                                 "factor grows faster than the particles: {:.3g} GB measured at "
                                 "{} x {}), more than this machine's {:.3g} GB; use "
                                 "pcg-multigrid or pcg-reduced",
                                 scene.cloth.rows, scene.cloth.cols, needed / 1e9,
                                 measured_bytes / 1e9, measured_side, measured_side,
                                 available_bytes / 1e9));
}

void check_run_limits(const Scene& scene, const IntegratorOptions& options,
                      const std::string& integrator_field) {
  check_advances(scene, integrator_field + ".dt", options.dt);
  check_linear_solver_memory(scene, options, integrator_field, physical_memory_bytes());
  // A fixed step longer than the run would be cut to the duration: the run would not take the
  // step its scene names.
  if (!options.adaptive && scene.duration > 0.0 && options.dt > scene.duration)
    throw InputError(scene.file, integrator_field + ".dt",
                     "larger than duration (" + nlohmann::json(scene.duration).dump() +
                         " s): the run would take one step of the duration, not dt");
  if (options.adaptive) check_advances(scene, integrator_field + ".max_dt", options.max_dt);
  // A fixed run takes duration / dt steps, an adaptive one at least duration / max_dt: more
  // than max_steps allows is refused now, not after hours of steps (counted in double:
  // duration / dt can be far beyond any integer type).
  const std::string step_field = integrator_field + (options.adaptive ? ".max_dt" : ".dt");
  const double step = options.adaptive ? options.max_dt : options.dt;
  if (step <= 0.0) return;  // an adaptive run without a bound on its step
  const double steps = std::ceil(scene.duration / step);
  if (steps > static_cast<double>(options.max_steps))
    throw InputError(scene.file, step_field,
                     "duration / " + std::string(options.adaptive ? "max_dt" : "dt") + " = " +
                         nlohmann::json(steps).dump() + " steps, more than " + integrator_field +
                         ".max_steps = " + std::to_string(options.max_steps));
}

// A key changes the state at most once when pressed (release, attach, map) and once more when
// an attach completes; after each key, and at the start, each hand can take one hold; a hold
// pauses and resumes at most once per stretch of its hand's track.
double event_frames_bound(const HandTrack& track) {
  const auto keys = static_cast<double>(track.keys().size());
  const auto runs = static_cast<double>(track.runs(Hand::Left) + track.runs(Hand::Right));
  return 4.0 * keys + 2.0 + 2.0 * runs;
}

void check_output_rows(const Scene& scene, const IntegratorOptions& options, double event_frames) {
  const OutputOptions& out = scene.output;
  if (out.energy_interval == 0.0) {
    const double steps = options.adaptive ? static_cast<double>(options.max_steps)
                                          : std::ceil(scene.duration / options.dt);
    if (steps + 1.0 > limits::max_output_rows)
      throw InputError(scene.file, "output.energy_interval",
                       fmt::format("0 writes a row of energy.csv every step: up to {:.0f} steps "
                                   "({}), more than {:.0f} rows; give an interval",
                                   steps, options.adaptive ? "integrator.max_steps" : "duration / integrator.dt",
                                   limits::max_output_rows));
  }
  const double particles = static_cast<double>(scene.cloth.rows) * scene.cloth.cols;
  const std::pair<const char*, double> frame_outputs[] = {
      {"output.trace_interval", out.trace_interval},
      {"output.vtk_interval", out.vtk_interval},
      {"output.event_trace_interval", out.event_trace_interval}};
  for (const auto& [field, interval] : frame_outputs) {
    if (interval == 0.0) continue;
    const double rows = (scene.duration / interval + 1.0 + event_frames) * particles;
    if (rows > limits::max_output_rows)
      throw InputError(scene.file, field,
                       fmt::format("would write {:.4g} rows (particles x frames, with up to {:.0f} "
                                   "frames at the input's events), more than {:.0f}",
                                   rows, event_frames, limits::max_output_rows));
  }
}

}  // namespace drape
