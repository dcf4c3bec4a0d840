#include "integrators/registry/options_reader.hpp"

#include "core/io/json_reader.hpp"
#include "core/io/scene_limits.hpp"
#include "integrators/arkode/butcher_tableau.hpp"
#include "integrators/registry/registry.hpp"

namespace drape {

namespace {

// Keys that only some integrators read: given to another one, they would be ignored without a
// word, and the run would not be the one its scene describes.
void reject_unused_keys(const JsonReader& in, const IntegratorOptions& o) {
  const NamedKeys& named = named_keys_of(o.name);
  const bool arkode = named.error_tolerances;
  const bool newton = named.newton_stages;
  const bool linear = named.linear_solves;
  const bool converged = named.solve && o.solve == "converged";
  const struct {
    const char* key;
    bool used;
    const char* users;
  } keys[] = {
      {"rtol", arkode || converged,
       "the arkode-* integrators and, with solve = converged, implicit-euler and bdf2"},
      {"atol", arkode || converged,
       "the arkode-* integrators and, with solve = converged, implicit-euler and bdf2"},
      {"max_dt", o.adaptive, "adaptive runs"},
      {"max_newton_iters", newton || converged,
       "arkode-dirk, arkode-imex and, with solve = converged, implicit-euler and bdf2"},
      {"nonlinear_solver", newton, "arkode-dirk and arkode-imex"},
      {"solve", named.solve, "implicit-euler and bdf2"},
      {"exact_solve", uses_line_search(o),
       "arkode-dirk and arkode-imex with nonlinear_solver = line-search and, with "
       "solve = converged, implicit-euler and bdf2"},
      {"imex_split", named.imex_split, "arkode-imex"},
      {"max_step_halvings", (newton && !o.adaptive) || converged,
       "fixed-step arkode-dirk and arkode-imex (adaptive runs shrink a failed step themselves) "
       "and, with solve = converged, implicit-euler and bdf2"},
      {"linear_tolerance", linear, "implicit-euler, bdf2, arkode-dirk and arkode-imex"},
      {"max_linear_iters", linear, "implicit-euler, bdf2, arkode-dirk and arkode-imex"},
  };
  for (const auto& k : keys)
    if (!k.used && in.has(k.key))
      throw in.error(k.key, "not used by this run of '" + o.name + "': only " + k.users +
                                " read it");
}

// A declared key's value, checked against its type and range.
nlohmann::json read_setting(JsonReader& in, const SettingKey& key) {
  switch (key.type) {
    case SettingKey::Type::integer:
      return in.integer_in(key.name, static_cast<std::int64_t>(key.min),
                           static_cast<std::int64_t>(key.max), key.default_value.get<long>());
    case SettingKey::Type::number: {
      const double value = in.number(key.name, key.default_value.get<double>());
      const bool below = key.open_min ? !(value > key.min) : !(value >= key.min);
      const bool above = key.open_max ? !(value < key.max) : !(value <= key.max);
      if (below || above) throw in.error(key.name, "must be a " + key.range_text());
      return value;
    }
    case SettingKey::Type::boolean:
      return in.boolean(key.name, key.default_value.get<bool>());
    case SettingKey::Type::choice: {
      const std::string value = in.string(key.name, key.default_value.get<std::string>());
      for (const std::string& c : key.choices)
        if (c == value) return value;
      throw in.error(key.name, "unknown value '" + shorten(value) + "' (" + key.range_text() + ")");
    }
  }
  return nullptr;
}

}  // namespace

IntegratorOptions read_integrator_options(const nlohmann::json& object, const std::string& file,
                                          const std::string& path) {
  JsonReader in(object, file, path);
  IntegratorOptions o;
  o.name = in.string("name");
  if (!find_integrator(o.name))
    throw in.error("name", "unknown integrator '" + o.name + "' (see `drapelab integrators`)");
  o.adaptive = in.boolean("adaptive", o.adaptive);
  if (o.adaptive && !find_integrator(o.name)->adaptive)
    throw in.error("adaptive", "integrator '" + o.name + "' has no adaptive steps");
  o.dt = o.adaptive ? in.number("dt", 0.0) : in.number("dt");
  if (!o.adaptive || in.has("dt")) in.positive("dt", o.dt);
  // A choice given as "" is refused: leaving the key out takes the default, and an empty value
  // is mostly a failed command substitution (--set integrator.table="$(...)") that would
  // otherwise run the default method under the name of another.
  const auto choice = [&in](const std::string& key, const std::string& current) {
    const std::string value = in.string(key, current);
    if (in.has(key) && value.empty())
      throw in.error(key, "must not be empty (leave the key out for the default)");
    return value;
  };
  if (in.has("table") && object.at("table").is_object()) {
    if (o.name != "arkode-dirk")
      throw in.error("table", "an inline Butcher table is for arkode-dirk only");
    o.user_table = in.raw("table");
    const ButcherTableau tableau = read_butcher_tableau(o.user_table, file, in.field("table"));
    if (o.adaptive && tableau.d.empty())
      throw InputError(file, in.field("table") + ".d",
                       "adaptive steps need an embedded method: give its weights d");
  } else {
    o.table = choice("table", o.table);
  }
  // Above 1 (relative) or 1 m and 1 m/s (absolute) a tolerance no longer controls anything on a
  // cloth of metres: the error test and the stages' convergence test would pass at once.
  o.rtol = in.at_most("rtol", in.positive("rtol", in.number("rtol", o.rtol)), 1.0);
  o.atol = in.at_most("atol", in.positive("atol", in.number("atol", o.atol)), 1.0);
  o.max_dt = in.non_negative("max_dt", in.number("max_dt", o.max_dt));
  o.linear_solver = choice("linear_solver", o.linear_solver);
  o.max_newton_iters = in.integer("max_newton_iters", o.max_newton_iters);
  if (in.has("max_newton_iters") && o.max_newton_iters < 1)
    throw in.error("max_newton_iters", "must be at least 1");
  o.nonlinear_solver = choice("nonlinear_solver", o.nonlinear_solver);
  if (!o.nonlinear_solver.empty() && o.nonlinear_solver != "line-search" &&
      o.nonlinear_solver != "newton")
    throw in.error("nonlinear_solver", "unknown nonlinear solver '" + o.nonlinear_solver +
                                           "' (one of: line-search, newton)");
  o.imex_split = choice("imex_split", o.imex_split);
  if (!o.imex_split.empty() && o.imex_split != "springs" && o.imex_split != "springs+collision")
    throw in.error("imex_split", "unknown split '" + o.imex_split +
                                     "' (one of: springs, springs+collision)");
  o.solve = choice("solve", o.solve);
  if (!o.solve.empty() && o.solve != "linearised" && o.solve != "converged")
    throw in.error("solve", "unknown solve '" + o.solve + "' (one of: linearised, converged)");
  o.exact_solve = choice("exact_solve", o.exact_solve);  // checked with the linear solver's name
  o.max_step_halvings = in.integer("max_step_halvings", o.max_step_halvings);
  if (o.max_step_halvings < 0 || o.max_step_halvings > 30)
    throw in.error("max_step_halvings", "must be between 0 and 30");
  o.linear_tolerance = in.positive(
      "linear_tolerance", in.number("linear_tolerance", named_keys_of(o.name).linear_tolerance));
  // A relative residual of 1 is met by CG's zero start: no solve at all.
  if (o.linear_tolerance >= 1.0)
    throw in.error("linear_tolerance", "must be below 1 (a relative residual of 1 is met by "
                                       "the zero start: nothing would be solved)");
  o.max_linear_iters = in.integer("max_linear_iters", o.max_linear_iters);
  if (o.max_linear_iters < 1) throw in.error("max_linear_iters", "must be at least 1");
  o.max_steps = static_cast<long>(in.integer_in("max_steps", 1, limits::max_steps, o.max_steps));
  for (const SettingKey& key : find_integrator(o.name)->keys)
    o.settings[key.name] = read_setting(in, key);
  in.finish();
  reject_unused_keys(in, o);
  validate_integrator_choice(o, file, path);
  return o;
}

nlohmann::json to_json(const IntegratorOptions& o) {
  nlohmann::json written = {
      {"name", o.name},
      {"dt", o.dt},
      {"adaptive", o.adaptive},
      {"table", o.user_table.is_null() ? nlohmann::json(o.table) : o.user_table},
      {"rtol", o.rtol},
      {"atol", o.atol},
      {"max_dt", o.max_dt},
      {"linear_solver", o.linear_solver},
      {"max_newton_iters", max_newton_iters_of(o)},
      {"nonlinear_solver", nonlinear_solver_of(o)},
      {"solve", o.solve},
      {"exact_solve", uses_line_search(o) ? exact_solve_of(o) : std::string()},
      {"imex_split", o.imex_split},
      {"max_step_halvings", o.max_step_halvings},
      {"linear_tolerance", linear_tolerance_of(o)},
      {"max_linear_iters", o.max_linear_iters},
      {"max_steps", o.max_steps}};
  const IntegratorDeclaration* declaration = find_integrator(o.name);
  if (!declaration) return written;  // options built in code for no registered integrator
  for (const SettingKey& key : declaration->keys)
    written[key.name] = o.setting(key.name, declaration->keys);
  return written;
}

}  // namespace drape
