#pragma once
// The ARKODE Butcher tables drapelab accepts as `integrator.table`, by full ARKODE name.
#include <string>
#include <vector>

#include "integrators/arkode/sundials_handles.hpp"

namespace drape {

/// Which ARKODE integrator a table belongs to.
enum class ArkodeKind { explicit_rk, diagonally_implicit, imex };

/// One table (or IMEX pair) with the ARKODE tables it loads.
struct ArkodeTable {
  std::string name;      ///< the name `integrator.table` takes
  ArkodeKind kind;
  std::string explicit_table;  ///< ARKODE ERK table name, "" for DIRK tables
  std::string implicit_table;  ///< ARKODE DIRK table name, "" for ERK tables
};

/// Every built-in ARKODE table of SUNDIALS 6.4.1, ERK, then DIRK, then the IMEX pairs.
const std::vector<ArkodeTable>& arkode_tables();
/// The table named `name` of kind `kind`, or null.
const ArkodeTable* find_arkode_table(const std::string& name, ArkodeKind kind);
/// The table an integrator of kind `kind` uses when `integrator.table` is empty.
const std::string& default_arkode_table(ArkodeKind kind);

namespace detail {
/// Loads an ARKODE ERK or DIRK table by name (null name: no table).
ButcherTableHandle load_explicit_table(const ArkodeTable& table);
ButcherTableHandle load_implicit_table(const ArkodeTable& table);
/// The table that carries order, embedded order and stages (the DIRK half of a pair).
ButcherTableHandle load_main_table(const ArkodeTable& table);
}  // namespace detail

}  // namespace drape
