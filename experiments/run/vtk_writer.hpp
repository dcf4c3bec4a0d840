#pragma once
// Legacy VTK polydata files of the cloth and the object that ParaView opens as a time series
// (frame_00000.vtk, frame_00001.vtk, ...; each carries its time in a TIME field).
#include <Eigen/Core>
#include <filesystem>

#include "core/model/cloth_system.hpp"

namespace drape {

/// The cloth at time t: particles, one quad per grid cell, velocity and fixed flag per particle.
void write_cloth_vtk(const std::filesystem::path& file, const ClothSystem& system,
                     const Eigen::VectorXd& y, double t);
/// The object particles as vertices with their outward normals.
void write_dummy_vtk(const std::filesystem::path& file, const Dummy& dummy);

}  // namespace drape
