#include "experiments/sweep/experiment_tally.hpp"

#include <fmt/format.h>

namespace drape {

void ExperimentTally::count(const std::string& status) {
  if (status == "ok") ++ok;
  else if (status == "error") ++errors;
  else if (status == "crashed") ++crashed;
  else ++unstable;  // diverged or failed
}

std::string ExperimentTally::summary() const {
  return fmt::format("{} ok, {} diverged or failed, {} could not run, {} crashed, {} resumed", ok,
                     unstable, errors, crashed, skipped);
}

}  // namespace drape
