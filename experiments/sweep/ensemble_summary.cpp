#include "experiments/sweep/ensemble_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "experiments/sweep/results_table.hpp"

namespace drape {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Identity columns of results.csv that are not metrics even when numeric.
const std::set<std::string>& not_metrics() {
  static const std::set<std::string> names = {"index", "id",        "scene",   "status",
                                              "reason", "is_reference", "reference", "run_dir"};
  return names;
}

// P(0 < T < t) for Student's t by composite Simpson on the density (smooth, so 2000 panels
// give ~1e-12 for every dof >= 1 and t below the 0.9999 quantile).
double t_half_cdf(double t, int dof) {
  const double nu = dof;
  const double log_c = std::lgamma((nu + 1) / 2) - std::lgamma(nu / 2) - 0.5 * std::log(nu * M_PI);
  auto density = [&](double x) { return std::exp(log_c - (nu + 1) / 2 * std::log1p(x * x / nu)); };
  constexpr int panels = 2000;
  const double h = t / panels;
  double sum = density(0.0) + density(t);
  for (int k = 1; k < panels; ++k) sum += density(k * h) * (k % 2 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

}  // namespace

double student_t_quantile(double p, int dof) {
  double lo = 0.0, hi = 1.0;
  while (t_half_cdf(hi, dof) < p - 0.5) hi *= 2.0;
  for (int k = 0; k < 100 && hi - lo > 1e-12 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (t_half_cdf(mid, dof) < p - 0.5 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

SampleStats sample_stats(const std::vector<double>& values) {
  SampleStats s;
  s.n = static_cast<int>(values.size());
  s.mean = s.std = s.ci95 = nan;
  if (s.n == 0) return s;
  double sum = 0.0;
  for (const double v : values) sum += v;
  s.mean = sum / s.n;
  if (s.n < 2) return s;
  double squares = 0.0;
  for (const double v : values) squares += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(squares / (s.n - 1));
  s.ci95 = student_t_quantile(0.975, s.n - 1) * s.std / std::sqrt(static_cast<double>(s.n));
  return s;
}

void write_ensemble_summary(const std::filesystem::path& file,
                            const std::vector<std::string>& parameters,
                            const std::vector<nlohmann::json>& rows) {
  std::vector<std::string> keys = {"scene", "is_reference"};
  for (const auto& p : parameters)
    if (p != repeat_parameter) keys.push_back(p);
  std::set<std::string> skip(not_metrics());
  skip.insert(parameters.begin(), parameters.end());
  // Metrics: every column that is a number in some row, in first-seen order.
  std::vector<std::string> metrics;
  for (const auto& row : rows)
    for (const auto& item : row.items())
      if (item.value().is_number() && !item.value().is_boolean() && !skip.count(item.key()) &&
          std::find(metrics.begin(), metrics.end(), item.key()) == metrics.end())
        metrics.push_back(item.key());

  // Groups in the order of their first run.
  std::vector<nlohmann::json> group_keys;
  std::map<std::string, std::vector<const nlohmann::json*>> members;
  for (const auto& row : rows) {
    nlohmann::json key = nlohmann::json::object();
    for (const auto& k : keys) key[k] = row.contains(k) ? row[k] : nlohmann::json();
    auto& list = members[key.dump()];
    if (list.empty()) group_keys.push_back(key);
    list.push_back(&row);
  }

  std::vector<std::string> columns = keys;
  columns.push_back("n");
  for (const auto& m : metrics)
    for (const char* suffix : {"_mean", "_std", "_ci95"}) columns.push_back(m + suffix);
  std::vector<nlohmann::json> out;
  for (const auto& key : group_keys) {
    const auto& group = members[key.dump()];
    nlohmann::json row = key;
    row["n"] = group.size();
    for (const auto& m : metrics) {
      std::vector<double> values;
      for (const auto* r : group)
        if (r->contains(m) && (*r)[m].is_number()) values.push_back((*r)[m].get<double>());
      const SampleStats s = sample_stats(values);
      auto cell = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
      row[m + "_mean"] = cell(s.mean);
      row[m + "_std"] = cell(s.std);
      row[m + "_ci95"] = cell(s.ci95);
    }
    out.push_back(std::move(row));
  }
  write_results_csv(file, columns, out);
}

}  // namespace drape
