#include "core/fabrics/fabric.hpp"

#include <stdexcept>

namespace drape {

namespace {

// Wang, Ramamoorthi and O'Brien 2011, "Data-driven elastic models for cloth: modeling and
// measurement" (ACM TOG 30(4) 71), measured fabrics as distributed in the ARCSim material
// files of the Berkeley Garment Library (materials/<name>.json). From each file: `density`;
// `stretching` row 0 (the smallest-strain sample) as [k0, k1, k2, k3] of ARCSim's energy
// e = k0 e00^2 / 2 + k1 e00 e11 + k2 e11^2 / 2 + k3 e01^2 (Green strain), so C11 along the
// two weave directions is k0 and k2 and the shear stiffness is G = k3 / 2; `bending` column 0
// (smallest curvature) of its three rows (0, 45, 90 degrees), taken as B in N m.
Fabric wang2011(const std::string& name, const std::string& kind, double density, double k0,
                double k2, double k3, double b0, double b45, double b90) {
  Fabric f;
  f.name = name;
  f.kind = kind;
  f.source = "Wang, Ramamoorthi, O'Brien 2011, Data-driven elastic models for cloth (ACM TOG "
             "30(4):71); ARCSim/Berkeley Garment Library file materials/" + name + ".json";
  f.note = "converted: C11 = mean of stretching[0][0] and stretching[0][2] (the grid has one "
           "structural stiffness), G = stretching[0][3] / 2, B = mean of bending[0..2][0]";
  f.areal_density = density;
  f.tensile_stiffness = 0.5 * (k0 + k2);
  f.shear_stiffness = 0.5 * k3;
  f.bending_rigidity = (b0 + b45 + b90) / 3.0;
  return f;
}

std::vector<Fabric> make_fabrics() {
  Fabric paper;
  paper.name = "paper";
  paper.kind = "model";
  paper.source = "Mesuda, Inui, Horiba, Cloth Model Handling by The Combination of Some "
                 "Manipulations for Draping; as the shipped scenes (experiments/scenes/)";
  paper.note = "not a measurement: 50 N/m structural and shear springs at every spacing, no "
               "bending, 6e-5 kg per particle at 2 cm (0.15 kg/m^2)";
  paper.areal_density = 0.15;
  paper.tensile_stiffness = 100.0;  // C11 - G = 50 N/m structural springs
  paper.shear_stiffness = 50.0;
  paper.bending_rigidity = 0.0;
  return {
      paper,
      wang2011("gray-interlock", "knit", 0.187, 16.593832, 34.477123, 36.860302, 23.191698e-6,
               24.749964e-6, 14.267624e-6),
      wang2011("ivory-rib-knit", "knit", 0.276, 42.871021, 65.166023, 83.175644, 46.237591e-6,
               30.015930e-6, 32.243889e-6),
      wang2011("11oz-black-denim", "woven", 0.324, 205.352005, 1013.88629, 53.387184,
               64.196457e-6, 73.384567e-6, 96.951576e-6),
      wang2011("royal-target", "woven", 0.220, 2016.55456, 2034.97644, 104.759674,
               125.409805e-6, 107.997696e-6, 125.409805e-6),
  };
}

}  // namespace

const std::vector<Fabric>& fabrics() {
  static const std::vector<Fabric> all = make_fabrics();
  return all;
}

const Fabric* find_fabric(const std::string& name) {
  for (const Fabric& f : fabrics())
    if (f.name == name) return &f;
  return nullptr;
}

std::string fabric_names() {
  std::string out;
  for (const Fabric& f : fabrics()) out += (out.empty() ? "" : ", ") + f.name;
  return out;
}

FabricSprings fabric_springs(const Fabric& fabric, double spacing) {
  // docs/fabrics.md: on a square grid, structural springs k and shear springs k_s give
  // C11 = k + k_s and G = k_s per unit area, whatever the spacing.
  if (fabric.shear_stiffness >= fabric.tensile_stiffness)
    throw std::invalid_argument("fabric '" + fabric.name +
                                "': shear stiffness must be below the tensile stiffness");
  FabricSprings s;
  s.particle_mass = fabric.areal_density * spacing * spacing;
  s.k_shear = fabric.shear_stiffness;
  s.k_structural = fabric.tensile_stiffness - fabric.shear_stiffness;
  const double theta = fabric_bend_reference_angle;
  s.k_bending = 16.0 * fabric.bending_rigidity / (spacing * spacing * theta * theta);
  return s;
}

}  // namespace drape
