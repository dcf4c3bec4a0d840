#pragma once
// Merges the runs of an experiment's shards that ran elsewhere into one folder
// (docs/experiments.md, "Shards").
#include <filesystem>
#include <string>
#include <vector>

namespace drape {

/// Copies the runs of `sources` (other output folders of the same experiment) into out_dir and
/// writes out_dir/results.{csv,json} from every finished run; returns the ids still missing,
/// each followed by its result.json and what is wrong with it when it has one that is no
/// result of the run (result_row_problem). A source's run replaces only a run without a valid one.
std::vector<std::string> merge_results(const std::filesystem::path& out_dir,
                                       const std::vector<std::filesystem::path>& sources);

}  // namespace drape
