#include "experiments/cli/run_stats.hpp"

#include <fmt/format.h>

namespace drape {

std::string format_run_stats(const nlohmann::json& s) {
  const nlohmann::json& c = s["counters"];
  const auto line = [](const char* name, const std::string& value) {
    return fmt::format("  {:<22} {}\n", name, value);
  };
  const double sim_time = s["sim_time"], wall = s["wall_seconds"];
  std::string out = fmt::format("status: {}", s["status"].get<std::string>());
  if (s.contains("reason")) out += fmt::format(" at t = {:.6g} s: {}", s.value("time", 0.0),
                                               s["reason"].get<std::string>());
  out += "\n";
  const std::string method = s["table"].get<std::string>().empty()
                                 ? s["integrator"].get<std::string>()
                                 : fmt::format("{} ({})", s["integrator"].get<std::string>(),
                                               s["table"].get<std::string>());
  out += line("integrator", method + (s["adaptive"].get<bool>() ? ", adaptive" : ""));
  out += line("steps", fmt::format("{} (asked dt = {:.6g} s; taken mean {:.6g} s, min {:.6g} s, max {:.6g} s)",
                                   c["steps"].get<long>(), s["dt"].get<double>(),
                                   s["step_mean"].get<double>(), s["step_min"].get<double>(),
                                   s["step_max"].get<double>()));
  out += line("attempted steps", std::to_string(c["attempts"].get<long>()));
  out += line("rhs evaluations", std::to_string(c["rhs_evals"].get<long>()));
  out += line("newton iterations", std::to_string(c["newton_iters"].get<long>()));
  out += line("linear iterations", std::to_string(c["linear_iters"].get<long>()));
  out += line("jacobian setups", std::to_string(c["jacobian_setups"].get<long>()));
  out += line("error test failures", std::to_string(c["error_test_failures"].get<long>()));
  out += line("convergence failures", std::to_string(c["convergence_failures"].get<long>()));
  out += line("step halvings", std::to_string(c["step_halvings"].get<long>()));
  out += line("resets at events", std::to_string(c["resets"].get<long>()));
  out += line("events", std::to_string(s["events"].size()));
  out += line("energy drift", fmt::format("{:.3g} J max, {:.3g} relative",
                                          s["energy_drift_max_abs"].get<double>(),
                                          s["energy_drift_max_rel"].get<double>()));
  out += line("simulated time", fmt::format("{:.6g} s of {:.6g} s", sim_time, s["duration"].get<double>()));
  out += line("wall time", fmt::format("{:.3g} s ({:.3g} x real time)", wall,
                                       wall > 0.0 ? sim_time / wall : 0.0));
  for (const auto& warning : s.value("warnings", nlohmann::json::array()))
    out += "warning: " + warning.get<std::string>() + "\n";
  return out;
}

}  // namespace drape
