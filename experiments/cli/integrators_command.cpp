#include "experiments/cli/integrators_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "core/io/input_error.hpp"
#include "experiments/run/scene_simulation.hpp"
#include "integrators/explicit/stability_limit.hpp"
#include "integrators/arkode/arkode_tables.hpp"
#include "integrators/arkode/butcher_tableau.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {

int list_integrators(bool json) {
  if (json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& declaration : integrators()) list.push_back(declaration.to_json());
    fmt::print("{}\n", list.dump(2));
    return 0;
  }
  fmt::print("{:<19} {:<14} {:>5} {:>8}  {}\n", "integrator", "family", "order", "adaptive",
             "description");
  for (const auto& info : integrators()) {
    fmt::print("{:<19} {:<14} {:>5} {:>8}  {}\n", info.name, info.family, info.order,
               info.adaptive ? "yes" : "no", info.description);
    for (const SettingKey& key : info.keys)
      fmt::print("{:<19}   integrator.{}: {} ({})\n", "", key.name, key.description,
                 key.range_text());
  }
  const auto tables = integrator_tables();
  if (!tables.empty()) {
    fmt::print("\n{:<18} {:<36} {:>5} {:>8} {:>6}\n", "integrator", "table", "order",
               "embedded", "stages");
    for (const auto& t : tables)
      fmt::print("{:<18} {:<36} {:>5} {:>8} {:>6}\n", t.integrator, t.name, t.order,
                 t.embedded_order, t.stages);
  }
  return 0;
}

int print_dirk_table(const std::string& name) {
  const ArkodeTable* table = find_arkode_table(name, ArkodeKind::diagonally_implicit);
  if (table == nullptr)
    throw InputError("drapelab integrators", "--table",
                     "'" + shorten(name) +
                         "' is not an arkode-dirk table (drapelab integrators lists them)");
  // One line, so that it can be passed on as it is: --set integrator.table="$(...)". JSON keeps
  // every double exactly (17 significant digits), so the user table is the same method.
  fmt::print("{}\n",
             to_json(detail::to_butcher_tableau(detail::load_implicit_table(*table).get())).dump());
  return 0;
}

int print_stability_limit(const Scene& scene) {
  const SceneSimulation run(scene);
  const Eigen::VectorXd& y = run.simulation().state();
  const Eigen::Index n3 = y.size() / 2;
  // A large cloth takes minutes (docs/integrators/explicit.md, "Largest stable fixed step"): every
  // 10 s the products so far go to stderr, so that the wait is visibly work, not a hang.
  const auto start = std::chrono::steady_clock::now();
  auto next_report = start + std::chrono::seconds(10);
  const auto report = [&](long products) {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_report) return;
    next_report = now + std::chrono::seconds(10);
    fmt::print(stderr, "drapelab integrators --stability: {} products with the Jacobian, {:.0f} s\n",
               products, std::chrono::duration<double>(now - start).count());
  };
  const ExplicitStabilityLimit limit =
      explicit_stability_limit(run.system(), y.head(n3), y.tail(n3), 1000, report);
  fmt::print("{}: the cloth linearised at t = 0 ({} particles)\n", scene.file, n3 / 3);
  fmt::print("  fastest mode: omega = {:.6g} rad/s ({} products with the Jacobian)\n", limit.omega,
             limit.jacobian_products);
  // A complex omega^2 (the contact force is not a potential's): the bound is then an estimate.
  if (std::abs(limit.omega2_imaginary) > 1e-8 * limit.omega * limit.omega)
    fmt::print("  (omega^2 has an imaginary part {:.3g} /s^2: the Jacobian is not symmetric here "
               "and the bound below is an estimate)\n",
               limit.omega2_imaginary);
  fmt::print("  its damping rate: c = {:.6g} /s\n", limit.damping_rate);
  fmt::print("  leap-frog and symplectic Euler stable below dt = {:.6g} ms "
             "(dt^2 omega^2 + 2 dt c < 4; without damping 2 / omega = {:.6g} ms)\n",
             1e3 * limit.damped, 1e3 * limit.undamped);
  return 0;
}

}  // namespace drape
