#pragma once
// The files a run writes (docs/model.md section 9), the contract that scripts and analysis/ read:
// energy.csv, state.csv and summary.json, numbers with round-trip precision.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/model/cloth_system.hpp"

namespace drape {

/// Opens a file for writing; throws std::runtime_error naming it when it cannot.
std::ofstream open_for_writing(const std::filesystem::path& file);
/// state.csv: `index,row,col,x,y,z,vx,vy,vz,fixed` for every cloth particle.
void write_state_csv(const std::filesystem::path& file, const ClothSystem& system,
                     const Eigen::VectorXd& y);
/// dummy.csv: `index,section,point,x,y,z,nx,ny,nz` for every object particle.
void write_dummy_csv(const std::filesystem::path& file, const Dummy& dummy);
/// Writes JSON with round-trip precision, creating nothing partial on failure.
void write_json(const std::filesystem::path& file, const nlohmann::json& value);

}  // namespace drape
