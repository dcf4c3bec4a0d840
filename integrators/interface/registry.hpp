#pragma once
// The list of integrators: names, kinds, orders, and the factory the runner calls.
#include <memory>
#include <string>
#include <vector>

#include "integrators/interface/integrator.hpp"
#include "integrators/interface/integrator_options.hpp"

namespace drape {

/// What an integrator is and what it supports.
struct IntegratorInfo {
  std::string name;
  std::string kind;         ///< explicit, implicit or imex
  int order;                ///< order of accuracy of its default method
  bool adaptive;            ///< supports error-controlled steps
  std::string description;
};

/// One ARKODE Butcher table (or IMEX pair) that an integrator accepts.
struct TableInfo {
  std::string integrator;
  std::string name;  ///< full ARKODE_... name
  int order;
  int embedded_order;
  int stages;
};

/// Every integrator, in the order `drapelab integrators` lists them.
const std::vector<IntegratorInfo>& integrators();
/// Every table usable through `integrator.table`.
std::vector<TableInfo> integrator_tables();
/// The integrator named `name`, or null.
const IntegratorInfo* find_integrator(const std::string& name);
/// Checks table and linear-solver choices against the integrator; throws InputError.
void validate_integrator_choice(const IntegratorOptions& options, const std::string& file,
                                const std::string& path);
/// Builds the integrator the options name, stepping `system`.
std::unique_ptr<Integrator> make_integrator(const IntegratorOptions& options,
                                            ClothSystem& system);

}  // namespace drape
