#pragma once
// Fabric presets from published measurements and the formulas that turn a sheet's measured
// stiffness into the paper's springs (docs/fabrics.md; docs/model.md section 2).
#include <string>
#include <vector>

namespace drape {

/// A fabric as a membrane with bending: the measured values, their source, and how they were read.
struct Fabric {
  std::string name;
  std::string kind;    ///< knit, woven or model
  std::string source;  ///< paper, table or file the numbers come from
  std::string note;    ///< which numbers were converted, averaged or estimated, and how
  double areal_density = 0.0;      ///< rho_A [kg/m^2]
  double tensile_stiffness = 0.0;  ///< C11 [N/m]: stress per strain along a grid line, sheet held laterally
  double shear_stiffness = 0.0;    ///< G [N/m]: in-plane shear stress per engineering shear strain
  double bending_rigidity = 0.0;   ///< B [N m]: bending moment per width per curvature
};

/// What a fabric becomes on a grid of one spacing (docs/fabrics.md, "From a sheet to springs").
struct FabricSprings {
  double particle_mass = 0.0;  ///< rho_A h^2 [kg]
  double k_structural = 0.0;   ///< C11 - G [N/m]
  double k_shear = 0.0;        ///< G [N/m]
  double k_bending = 0.0;      ///< 16 B / (h^2 theta_ref^2) [N/m]
};

/// The fold angle at one particle where a bending spring's energy equals the sheet's
/// (a linear spring across 2h stores energy quartic in the fold angle: docs/fabrics.md).
constexpr double fabric_bend_reference_angle = 1.0;  // [rad]

/// Every preset, in the order `drapelab fabrics` lists them.
const std::vector<Fabric>& fabrics();
/// The preset of that name, or null.
const Fabric* find_fabric(const std::string& name);
/// Springs and mass that discretise `fabric` on a square grid of spacing h [m].
/// Throws std::invalid_argument when G >= C11 (no positive structural spring reproduces it).
FabricSprings fabric_springs(const Fabric& fabric, double spacing);
/// The names of every preset, comma-separated (for error messages).
std::string fabric_names();

}  // namespace drape
