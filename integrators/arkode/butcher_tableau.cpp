#include "integrators/arkode/butcher_tableau.hpp"

#include <algorithm>
#include <cmath>

#include "core/io/json_reader.hpp"

namespace drape {

namespace {

// Published tables are often given to 10 or 11 digits: ARKODE's own CASH_5_2_4 and CASH_5_3_4
// have rows of A that sum to c within 1.1e-11 and weights that sum to 1 within 7.8e-12
// (`drapelab integrators --table` prints them for reuse as user tables), BILLINGTON_3_3_2
// within 1.0e-12. 1e-10 accepts them and still rejects a wrong digit up to the ninth.
constexpr double tolerance = 1e-10;

// No published method has a coefficient near this (the largest in ARKODE's own DIRK tables is
// 35.1); near 1e300 the stage sums ARKODE forms overflow and the run fails instead of being
// refused.
constexpr double max_coefficient = 1e3;

// ARKODE's own tables have at most 8 stages; a user table of thousands (a 3000-stage identity
// took 1.7 GB) is no method anyone studies.
constexpr std::size_t max_stages = 64;

// ARKODE counts a stage implicit when |A_ii| exceeds 1e-12 (arkStep_CheckButcherTables) and
// refuses a table with none only when the run starts.
constexpr double implicit_diagonal = 1e-12;

bool near(double value, double expected) { return std::abs(value - expected) <= tolerance; }

double sum(const std::vector<double>& values) {
  double total = 0.0;
  for (const double v : values) total += v;
  return total;
}

std::vector<double> read_matrix_rows(JsonReader& in, std::size_t s) {
  const nlohmann::json& a = in.raw("A");
  if (!a.is_array() || a.size() != s)
    throw in.error("A", "must be an array of " + std::to_string(s) + " rows (one per node of c)");
  std::vector<double> flat;
  for (const auto& row : a) {
    if (!row.is_array() || row.size() != s)
      throw in.error("A", "must be square: every row has " + std::to_string(s) + " numbers");
    for (const auto& value : row) {
      if (!value.is_number()) throw in.error("A", "must hold numbers");
      flat.push_back(in.within("A", value.get<double>(), max_coefficient));
    }
  }
  return flat;
}

// in.numbers(key), each within +-max_coefficient.
std::vector<double> coefficients(JsonReader& in, const std::string& key) {
  std::vector<double> values = in.numbers(key);
  for (const double x : values) in.within(key, x, max_coefficient);
  return values;
}

}  // namespace

int tableau_order(const ButcherTableau& t, const std::vector<double>& w) {
  const std::size_t s = t.c.size();
  double bc = 0.0, bc2 = 0.0, bac = 0.0;
  for (std::size_t i = 0; i < s; ++i) {
    bc += w[i] * t.c[i];
    bc2 += w[i] * t.c[i] * t.c[i];
    double ac = 0.0;
    for (std::size_t j = 0; j < s; ++j) ac += t.A[i][j] * t.c[j];
    bac += w[i] * ac;
  }
  // Butcher's conditions: sum w = 1; sum w c = 1/2; sum w c^2 = 1/3 and w^T A c = 1/6.
  if (!near(sum(w), 1.0)) return 0;
  if (!near(bc, 0.5)) return 1;
  if (!near(bc2, 1.0 / 3.0) || !near(bac, 1.0 / 6.0)) return 2;
  return 3;
}

ButcherTableau read_butcher_tableau(const nlohmann::json& object, const std::string& file,
                                    const std::string& path) {
  JsonReader in(object, file, path);
  ButcherTableau t;
  t.c = coefficients(in, "c");
  const std::size_t s = t.c.size();
  if (s == 0) throw in.error("c", "must hold at least one node");
  if (s > max_stages)
    throw in.error("c", "has " + std::to_string(s) + " nodes, more than the limit of " +
                            std::to_string(max_stages) + " stages");
  const std::vector<double> flat = read_matrix_rows(in, s);
  t.A.assign(s, std::vector<double>(s));
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = 0; j < s; ++j) t.A[i][j] = flat[i * s + j];
  for (std::size_t i = 0; i < s; ++i)
    for (std::size_t j = i + 1; j < s; ++j)
      if (t.A[i][j] != 0.0)
        throw in.error("A", "must be lower triangular for arkode-dirk (row " + std::to_string(i) +
                                ", column " + std::to_string(j) + " is not 0)");
  bool implicit = false;
  for (std::size_t i = 0; i < s; ++i) implicit = implicit || std::abs(t.A[i][i]) > implicit_diagonal;
  if (!implicit)
    throw in.error("A", "has no diagonal entry beyond 1e-12 in magnitude: that is an explicit "
                        "method to ARKODE, and arkode-dirk needs at least one implicit stage");
  for (std::size_t i = 0; i < s; ++i) {
    double row = 0.0;
    for (const double a : t.A[i]) row += a;
    if (!near(row, t.c[i]))
      throw in.error("c", "node " + std::to_string(i) + " must equal row " + std::to_string(i) +
                              " of A summed (" + std::to_string(row) + ")");
  }
  t.b = coefficients(in, "b");
  if (t.b.size() != s) throw in.error("b", "must have one weight per node of c");
  if (!near(sum(t.b), 1.0)) throw in.error("b", "weights must sum to 1");
  if (in.has("d")) {
    t.d = coefficients(in, "d");
    if (t.d.size() != s) throw in.error("d", "must have one weight per node of c");
    if (!near(sum(t.d), 1.0)) throw in.error("d", "weights must sum to 1");
    // The error estimate is the difference of the two solutions: with d = b it is zero, and an
    // adaptive run would take every step it tries, whatever its error.
    bool same = true;
    for (std::size_t i = 0; i < s; ++i) same = same && near(t.d[i], t.b[i]);
    if (same) throw in.error("d", "equals b: an embedding must differ from b to estimate the error");
  }
  const int b_order = tableau_order(t, t.b);
  t.q = in.integer("q", b_order);
  if (t.q < 1) throw in.error("q", "must be at least 1");
  if (std::min(t.q, 3) > b_order)
    throw in.error("q", "b satisfies the order conditions up to order " +
                            std::to_string(b_order) + " only");
  if (t.d.empty()) {
    if (in.has("p")) throw in.error("p", "an embedding order needs embedding weights d");
  } else {
    const int d_order = tableau_order(t, t.d);
    t.p = in.integer("p", d_order);
    if (t.p < 1) throw in.error("p", "must be at least 1");
    if (std::min(t.p, 3) > d_order)
      throw in.error("p", "d satisfies the order conditions up to order " +
                              std::to_string(d_order) + " only");
  }
  in.finish();
  return t;
}

nlohmann::json to_json(const ButcherTableau& t) {
  nlohmann::json out = {{"c", t.c}, {"A", t.A}, {"b", t.b}, {"q", t.q}};
  if (!t.d.empty()) {
    out["d"] = t.d;
    out["p"] = t.p;
  }
  return out;
}

namespace detail {

ButcherTableHandle create_butcher_table(const ButcherTableau& t) {
  const std::size_t s = t.c.size();
  std::vector<double> c = t.c, b = t.b, d = t.d, a;
  for (const auto& row : t.A) a.insert(a.end(), row.begin(), row.end());
  return ButcherTableHandle(check_created(
      ARKodeButcherTable_Create(static_cast<int>(s), t.q, t.p, c.data(), a.data(), b.data(),
                                d.empty() ? nullptr : d.data()),
      "ARKodeButcherTable_Create"));
}

ButcherTableau to_butcher_tableau(const ARKodeButcherTable table) {
  const std::size_t s = static_cast<std::size_t>(table->stages);
  ButcherTableau t;
  t.c.assign(table->c, table->c + s);
  t.b.assign(table->b, table->b + s);
  if (table->d) t.d.assign(table->d, table->d + s);
  for (std::size_t i = 0; i < s; ++i) t.A.emplace_back(table->A[i], table->A[i] + s);
  t.q = table->q;
  t.p = table->p;
  return t;
}

}  // namespace detail

}  // namespace drape
