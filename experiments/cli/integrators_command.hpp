#pragma once
// `drapelab integrators`: the integrators and ARKODE tables, and one DIRK table's coefficients
// in the form `integrator.table` accepts inline (docs/integrators/arkode.md, "User tables").
#include <string>

#include "core/scene/scene.hpp"

namespace drape {

/// Prints the integrators with their own keys, and the ARKODE tables with their orders; with
/// `json`, the integrators' declarations as a JSON list. Returns exit status 0.
int list_integrators(bool json);
/// Prints the arkode-dirk table `name` (e.g. ARKODE_KVAERNO_4_2_3) as an inline tableau:
/// {"c", "A", "b", "d", "q", "p"}, to study or change it as a user table. Throws InputError
/// (field `--table`) for a name that is not an arkode-dirk table.
int print_dirk_table(const std::string& name);
/// Prints the stability limit of leap-frog and symplectic Euler on `scene`'s cloth at its start
/// (integrators/explicit/stability_limit.hpp). Returns exit status 0.
int print_stability_limit(const Scene& scene);

}  // namespace drape
