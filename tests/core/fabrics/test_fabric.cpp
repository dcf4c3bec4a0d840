// Fabric presets and their springs (docs/fabrics.md): each derived value against a hand
// computation from the numbers the preset cites.
#include <gtest/gtest.h>

#include <set>

#include "core/fabrics/fabric.hpp"

namespace drape {
namespace {

const Fabric& fabric(const std::string& name) {
  const Fabric* f = find_fabric(name);
  if (!f) throw std::runtime_error("no fabric " + name);
  return *f;
}

TEST(Fabric, PaperPresetIsTheShippedScenesSprings) {
  const FabricSprings s = fabric_springs(fabric("paper"), 0.02);
  EXPECT_DOUBLE_EQ(s.particle_mass, 6e-5);  // 0.15 kg/m^2 * (0.02 m)^2
  EXPECT_DOUBLE_EQ(s.k_structural, 50.0);
  EXPECT_DOUBLE_EQ(s.k_shear, 50.0);
  EXPECT_EQ(s.k_bending, 0.0);
  EXPECT_DOUBLE_EQ(fabric_springs(fabric("paper"), 0.05).k_structural, 50.0)
      << "springs of the paper preset do not depend on the spacing";
}

TEST(Fabric, DenimAtOneCentimetre) {
  // ARCSim 11oz-black-denim.json: stretching[0] = [205.352005, ., 1013.88629, 53.387184],
  // bending[.][0] = 64.196457e-6, 73.384567e-6, 96.951576e-6, density 0.324.
  const FabricSprings s = fabric_springs(fabric("11oz-black-denim"), 0.01);
  EXPECT_NEAR(s.particle_mass, 3.24e-5, 1e-15);
  EXPECT_NEAR(s.k_shear, 26.693592, 1e-9);                 // 53.387184 / 2
  EXPECT_NEAR(s.k_structural, 609.6191475 - 26.693592, 1e-9);  // mean(k0, k2) - G
  EXPECT_NEAR(s.k_bending, 16.0 * 78.177533333e-6 / 1e-4, 1e-8);  // 16 B / h^2, theta_ref 1
}

TEST(Fabric, InterlockKnitAtTwoCentimetres) {
  const FabricSprings s = fabric_springs(fabric("gray-interlock"), 0.02);
  EXPECT_NEAR(s.particle_mass, 7.48e-5, 1e-15);
  EXPECT_NEAR(s.k_shear, 18.430151, 1e-9);
  EXPECT_NEAR(s.k_structural, 25.5354775 - 18.430151, 1e-9);
  EXPECT_NEAR(s.k_bending, 16.0 * 20.736428667e-6 / 4e-4, 1e-8);
}

TEST(Fabric, BendingSpringsScaleAsOneOverSpacingSquaredAndMassAsSpacingSquared) {
  for (const Fabric& f : fabrics()) {
    const FabricSprings a = fabric_springs(f, 0.01), b = fabric_springs(f, 0.02);
    EXPECT_NEAR(a.k_bending, 4.0 * b.k_bending, 1e-12 * a.k_bending) << f.name;
    EXPECT_NEAR(4.0 * a.particle_mass, b.particle_mass, 1e-18) << f.name;
    EXPECT_GT(a.k_structural, 0.0) << f.name;
  }
}

TEST(Fabric, EveryPresetNamesItsSourceAndNamesAreUnique) {
  std::set<std::string> names;
  for (const Fabric& f : fabrics()) {
    EXPECT_FALSE(f.source.empty()) << f.name;
    EXPECT_FALSE(f.note.empty()) << f.name;
    EXPECT_TRUE(names.insert(f.name).second) << f.name;
  }
  EXPECT_GE(names.count("paper"), 1u);
  EXPECT_EQ(find_fabric("velvet"), nullptr);
}

TEST(Fabric, ShearAboveTensileIsRefused) {
  Fabric f;
  f.name = "odd";
  f.tensile_stiffness = 10.0;
  f.shear_stiffness = 10.0;
  EXPECT_THROW(fabric_springs(f, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace drape
