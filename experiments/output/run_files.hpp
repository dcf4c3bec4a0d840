#pragma once
// The files a run writes (docs/model.md section 9), the contract that scripts and analysis/ read:
// energy.csv, state.csv and summary.json, numbers with round-trip precision.
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "core/model/cloth_system.hpp"
#include "core/io/output_error.hpp"

namespace drape {

// OutputError (core/io/output_error.hpp): a run stops at its first failed write with exit
// status 4 and leaves no summary.json (docs/outputs.md).

/// Throws OutputError naming `file` and the system's reason once `out` has failed. Rows are
/// buffered: a failed write shows when the buffer is written, within a buffer's length.
void check_written(const std::ostream& out, const std::filesystem::path& file);
/// Flushes `out`, then check_written: the end of a file.
void finish_written(std::ostream& out, const std::filesystem::path& file);
/// Opens a file for writing; throws OutputError naming it when it cannot.
std::ofstream open_for_writing(const std::filesystem::path& file);
/// state.csv: `index,row,col,x,y,z,vx,vy,vz,fixed` for every cloth particle.
void write_state_csv(const std::filesystem::path& file, const ClothSystem& system,
                     const Eigen::VectorXd& y);
/// dummy.csv: `index,section,point,x,y,z,nx,ny,nz` for every object particle.
void write_dummy_csv(const std::filesystem::path& file, const Dummy& dummy);
/// Writes `file` through `write` under the name `file` + `suffix`, then renames it: a reader
/// never sees half a file, and a failed or killed writer leaves at most the temporary.
void write_file_atomic(const std::filesystem::path& file, const std::string& suffix,
                       const std::function<void(std::ostream&)>& write);
/// Writes JSON with round-trip precision through write_file_atomic. The suffix `.tmp` is a run
/// file (run_folder.cpp); processes writing one file alike each pass their own (results_table).
void write_json(const std::filesystem::path& file, const nlohmann::json& value,
                const std::string& suffix = ".tmp");

}  // namespace drape
