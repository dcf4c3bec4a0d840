#include "experiments/sweep/plan_size.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "core/io/input_error.hpp"

namespace drape {

namespace {

// Each factor of the plan with the field that sets it.
std::vector<std::pair<const char*, double>> factors(const Experiment& e) {
  double sweep = 1.0;
  for (const auto& [key, values] : e.sweep) sweep *= static_cast<double>(values.size());
  return {{"scenes", static_cast<double>(e.scenes.size())},
          {"cases", static_cast<double>(std::max<std::size_t>(e.cases.size(), 1))},
          {"sweep", sweep},
          {"repeats", static_cast<double>(std::max(e.repeats, 1))}};
}

}  // namespace

double plan_size_bound(const Experiment& experiment) {
  double runs = experiment.reference.empty() ? 1.0 : 2.0;
  for (const auto& [field, factor] : factors(experiment)) runs *= factor;
  return runs;
}

void check_plan_size(const Experiment& experiment) {
  const double runs = plan_size_bound(experiment);
  if (runs <= static_cast<double>(max_plan_runs)) return;
  const auto all = factors(experiment);
  const auto largest = std::max_element(
      all.begin(), all.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  throw InputError(experiment.file, largest->first,
                   fmt::format("{:.0f} runs{}, more than the limit {}", runs,
                               experiment.reference.empty() ? "" : " with their references",
                               max_plan_runs));
}

}  // namespace drape
