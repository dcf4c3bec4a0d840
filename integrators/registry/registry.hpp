#pragma once
// The list of integrators (each one's declaration) and the factory the runner calls.
#include <memory>
#include <string>
#include <vector>

#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_declaration.hpp"
#include "integrators/interface/integrator_options.hpp"

namespace drape {

/// One ARKODE Butcher table (or IMEX pair) that an integrator accepts.
struct TableInfo {
  std::string integrator;
  std::string name;  ///< full ARKODE_... name
  int order;
  int embedded_order;
  int stages;
};

/// Every integrator, in the order `drapelab integrators` lists them.
const std::vector<IntegratorDeclaration>& integrators();
/// Every table usable through `integrator.table`.
std::vector<TableInfo> integrator_tables();
/// The integrator named `name`, or null.
const IntegratorDeclaration* find_integrator(const std::string& name);
/// The named keys the integrator `name` declares; none for a name no integrator has (options
/// built in code before their name is checked).
const NamedKeys& named_keys_of(const std::string& name);

// integrator_options.hpp's readings of the options, against the declaration of their name.
std::string linear_solver_of(const IntegratorOptions& options);
double linear_tolerance_of(const IntegratorOptions& options);
std::string nonlinear_solver_of(const IntegratorOptions& options);
bool uses_line_search(const IntegratorOptions& options);
int max_newton_iters_of(const IntegratorOptions& options);

/// Checks table and linear-solver choices against the integrator; throws InputError.
void validate_integrator_choice(const IntegratorOptions& options, const std::string& file,
                                const std::string& path);
/// Builds the integrator the options name, stepping `system`.
std::unique_ptr<Integrator> make_integrator(const IntegratorOptions& options,
                                            ClothSystem& system);

}  // namespace drape
