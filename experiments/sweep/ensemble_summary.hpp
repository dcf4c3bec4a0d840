#pragma once
// summary.csv of an experiment with `repeats` (docs/experiments.md, "Ensembles"): one row per
// group of repeats (scene x case x swept values) with n and, for every numeric metric, its
// sample mean, standard deviation and 95% confidence half-width.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace drape {

/// The scene key whose values tell the repeats of one group apart.
inline constexpr const char* repeat_parameter = "perturbation.seed";

/// n, mean, sample standard deviation (n - 1) and Student-t 95% half-width t_{0.975, n-1} s / sqrt(n).
struct SampleStats {
  int n = 0;
  double mean = 0.0;
  double std = 0.0;   ///< NaN for n < 2
  double ci95 = 0.0;  ///< NaN for n < 2
};

/// Statistics of a sample (empty: n = 0, everything else NaN).
SampleStats sample_stats(const std::vector<double>& values);
/// The p-quantile of Student's t with `dof` degrees of freedom (p in (0.5, 1), dof >= 1).
double student_t_quantile(double p, int dof);
/// Groups result rows by scene, is_reference and every parameter but the repeat one, and writes
/// one CSV row per group (columns: scene, is_reference, the parameters, n, then per metric
/// <metric>_mean, <metric>_std, <metric>_ci95).
void write_ensemble_summary(const std::filesystem::path& file,
                            const std::vector<std::string>& parameters,
                            const std::vector<nlohmann::json>& rows);

}  // namespace drape
