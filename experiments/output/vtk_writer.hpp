#pragma once
// Legacy VTK polydata files of the cloth and the object that ParaView opens as a time series
// (frame_00000.vtk, frame_00001.vtk, ...; each carries its time in a TIME field, and
// frames.vtk.series lists them with their times: vtk_series.hpp).
#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "core/model/cloth_system.hpp"

namespace drape {

/// Per-particle data of a frame that the state alone does not give (docs/outputs.md, frames/).
struct ClothFrameData {
  std::vector<int> held;     ///< 1 where a hand holds the particle, else 0
  std::vector<int> contact;  ///< object particle within the collision threshold, -1 for none
};

/// The cloth at time t: particles, one quad per grid cell, and per particle velocity, fixed,
/// held and contact.
void write_cloth_vtk(const std::filesystem::path& file, const ClothSystem& system,
                     const Eigen::VectorXd& y, double t, const ClothFrameData& data);
/// The object particles as vertices with their outward normals.
void write_dummy_vtk(const std::filesystem::path& file, const Dummy& dummy);

}  // namespace drape
