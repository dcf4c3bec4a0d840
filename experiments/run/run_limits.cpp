#include "experiments/run/run_limits.hpp"

#include <cmath>

#include "core/scene/input_error.hpp"
#include "core/scene/scene_limits.hpp"

namespace drape {

namespace {

void check_advances(const Scene& scene, const std::string& field, double step) {
  // Near the end t + step == t once step < duration 2^-53; 2^-50 leaves room for round-off.
  if (step > 0.0 && step < scene.duration * limits::min_relative_step)
    throw InputError(scene.file, field,
                     "too small to advance time over duration " +
                         nlohmann::json(scene.duration).dump() + " s (at least duration x 2^-50)");
}

}  // namespace

void check_run_limits(const Scene& scene, const IntegratorOptions& options,
                      const std::string& integrator_field) {
  check_advances(scene, integrator_field + ".dt", options.dt);
  if (options.adaptive) {
    check_advances(scene, integrator_field + ".max_dt", options.max_dt);
    return;
  }
  // Counted in double: duration / dt can be far beyond any integer type.
  const double steps = std::ceil(scene.duration / options.dt);
  if (steps > static_cast<double>(options.max_steps))
    throw InputError(scene.file, integrator_field + ".dt",
                     "duration / dt = " + nlohmann::json(steps).dump() +
                         " steps, more than " + integrator_field + ".max_steps = " +
                         std::to_string(options.max_steps));
}

}  // namespace drape
