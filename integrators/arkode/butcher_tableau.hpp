#pragma once
// A user's own diagonally implicit Butcher table, given inline as `integrator.table` of
// arkode-dirk (docs/integrators/arkode.md, "User tables"): {"c": [...], "A": [[...]], "b": [...],
// optional "d" (embedding), "q" (order), "p" (embedding order)}, checked for consistency and
// handed to ARKODE through ARKodeButcherTable_Create.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "integrators/arkode/sundials_handles.hpp"

namespace drape {

/// The tableau of an s-stage diagonally implicit Runge-Kutta method.
struct ButcherTableau {
  std::vector<double> c, b, d;       ///< nodes, weights, embedding weights (empty: none)
  std::vector<std::vector<double>> A;  ///< s x s, lower triangular
  int q = 0;                         ///< order
  int p = 0;                         ///< embedding order (0 without d)
};

/// Reads and checks an inline tableau: A square and lower triangular, sizes that match, the
/// weights summing to 1 and A's row sums equal to c within 1e-10, and q, p satisfied by the
/// order conditions up to order 3 (when absent, the highest order up to 3 they satisfy).
/// Errors name `file` and `path.<field>`.
ButcherTableau read_butcher_tableau(const nlohmann::json& object, const std::string& file,
                                    const std::string& path);
nlohmann::json to_json(const ButcherTableau& tableau);

/// The highest order up to 3 whose conditions the weights `w` satisfy with A and c (0: not even
/// consistent).
int tableau_order(const ButcherTableau& tableau, const std::vector<double>& w);

namespace detail {
/// The tableau as an ARKODE table.
ButcherTableHandle create_butcher_table(const ButcherTableau& tableau);
/// An ARKODE table as a tableau (c, A, b, d, q, p copied).
ButcherTableau to_butcher_tableau(const ARKodeButcherTable table);
}  // namespace detail

}  // namespace drape
