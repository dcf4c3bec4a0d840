#pragma once
// The files a run writes (SPEC 9), the contract that scripts and analysis/ read:
// energy.csv, state.csv and summary.json, numbers with round-trip precision.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/cloth_system.hpp"

namespace drape {

/// energy.csv: `t,kinetic,spring,gravity,collision,total`, one row per output time.
class EnergyWriter {
 public:
  explicit EnergyWriter(const std::filesystem::path& file);
  void write(double t, const EnergyBreakdown& e);

 private:
  std::ofstream m_out;
};

/// state.csv: `index,row,col,x,y,z,vx,vy,vz,fixed` for every cloth particle.
void write_state_csv(const std::filesystem::path& file, const ClothSystem& system,
                     const Eigen::VectorXd& y);
/// dummy.csv: `index,section,point,x,y,z,nx,ny,nz` for every object particle.
void write_dummy_csv(const std::filesystem::path& file, const Dummy& dummy);
/// Writes JSON with round-trip precision, creating nothing partial on failure.
void write_json(const std::filesystem::path& file, const nlohmann::json& value);

}  // namespace drape
