// Scene validation (docs/model.md section 9): every class of bad input names the file and the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/io/input_error.hpp"
#include "core/scene/scene.hpp"
#include "tests/core/scene/scene_fixtures.hpp"

namespace drape {
namespace {

using testing::error_for;
using testing::valid_scene;
using testing::with;

TEST(Scene, ValidSceneParsesWithDefaults) {
  const Scene s = parse_scene(valid_scene(), "scene.json", ".");
  EXPECT_EQ(s.cloth.rows, 4);
  EXPECT_EQ(s.cloth.k_shear, 50.0) << "shear defaults to the structural stiffness";
  EXPECT_EQ(s.cloth.k_bending, 0.0);
  EXPECT_EQ(s.cloth.col_dir, Vec3::UnitX());
  EXPECT_EQ(s.cloth.row_dir, -Vec3::UnitY());
  EXPECT_EQ(s.forces.gravity, Vec3(0, -9.81, 0));
  ASSERT_EQ(s.pins.size(), 2u);
  EXPECT_EQ(s.pins[1].col, 4);
  EXPECT_TRUE(s.dummy.is_null());
  EXPECT_EQ(s.duration, 0.5);
  EXPECT_EQ(s.runaway_horizon, 0.5) << "the runaway bound's free fall lasts the run";
}

TEST(Scene, TheRunawayHorizonIsAtLeastTheDuration) {
  EXPECT_EQ(parse_scene(with("runaway_horizon=600"), "scene.json", ".").runaway_horizon, 600.0);
  EXPECT_EQ(error_for(with("runaway_horizon=0.4")),
            "scene.json: runaway_horizon: must be at least duration (0.5 s)");
  EXPECT_EQ(error_for(with("runaway_horizon=2e6")),
            "scene.json: runaway_horizon: must be at most 1000000.0, got 2000000.0");
}

TEST(Scene, AbsentDummyIsTheDressForm) {
  nlohmann::json scene = valid_scene();
  scene.erase("dummy");
  EXPECT_EQ(parse_scene(scene, "scene.json", ".").dummy, nlohmann::json({{"builtin", "dress-form"}}));
}

TEST(Scene, UnknownKeysAreErrors) {
  EXPECT_EQ(error_for(with("cloth.stiffness=3")), "scene.json: cloth.stiffness: unknown key");
  EXPECT_EQ(error_for(with("colour=1")), "scene.json: colour: unknown key");
  EXPECT_EQ(error_for(with("collision.modell=\"particle\"")),
            "scene.json: collision.modell: unknown key");
}

// docs/model.md section 4.12: mu in [0, 10] (default 0: no friction), epsilon_v in [1e-9, 100] m/s.
TEST(Scene, FrictionKeysAreReadAndCheckedAgainstTheirRanges) {
  const Scene defaults = parse_scene(valid_scene(), "scene.json", ".");
  EXPECT_EQ(defaults.forces.collision.friction, 0.0);
  EXPECT_EQ(defaults.forces.collision.friction_epsilon, 1e-3);
  const Scene set = parse_scene(with("collision.friction=0.5", "collision.friction_epsilon=0.01"),
                                "scene.json", ".");
  EXPECT_EQ(set.forces.collision.friction, 0.5);
  EXPECT_EQ(set.forces.collision.friction_epsilon, 0.01);
  EXPECT_EQ(error_for(with("collision.friction=-0.1")),
            "scene.json: collision.friction: must not be negative, got -0.1");
  EXPECT_EQ(error_for(with("collision.friction=11")),
            "scene.json: collision.friction: must be at most 10.0, got 11.0");
  EXPECT_EQ(error_for(with("collision.friction_epsilon=0")),
            "scene.json: collision.friction_epsilon: must be positive, got 0.0");
  EXPECT_EQ(error_for(with("collision.friction_epsilon=1e-12")),
            "scene.json: collision.friction_epsilon: must be at least 1e-09, got 1e-12");
  EXPECT_EQ(error_for(with("collision.friction_epsilon=1000")),
            "scene.json: collision.friction_epsilon: must be at most 100.0, got 1000.0");
}

TEST(Scene, MissingRequiredFieldsAreNamed) {
  nlohmann::json scene = valid_scene();
  scene["cloth"].erase("spacing");
  EXPECT_EQ(error_for(scene), "scene.json: cloth.spacing: required field is missing");
  scene = valid_scene();
  scene.erase("duration");
  EXPECT_EQ(error_for(scene), "scene.json: duration: required field is missing");
}

TEST(Scene, WrongTypes) {
  EXPECT_EQ(error_for(with("cloth.rows=\"four\"")),
            "scene.json: cloth.rows: expected an integer, got \"four\"");
  EXPECT_EQ(error_for(with("cloth.origin=[0, 1]")),
            "scene.json: cloth.origin: expected 3 numbers [x, y, z]");
  EXPECT_EQ(error_for(with("integrator=3")), "scene.json: integrator: expected an object");
}

TEST(Scene, OutOfRangeValues) {
  EXPECT_EQ(error_for(with("cloth.spacing=0")),
            "scene.json: cloth.spacing: must be at least 1e-06, got 0.0");
  EXPECT_EQ(error_for(with("cloth.particle_mass=-1")),
            "scene.json: cloth.particle_mass: must be at least 1e-12, got -1.0");
  EXPECT_EQ(error_for(with("cloth.rows=0")),
            "scene.json: cloth.rows: must be an integer from 1 to 4000000, got 0");
  EXPECT_EQ(error_for(with("cloth.k_shear=-2")),
            "scene.json: cloth.k_shear: must not be negative, got -2.0");
  EXPECT_EQ(error_for(with("duration=-1")), "scene.json: duration: must not be negative, got -1.0");
  EXPECT_EQ(error_for(with("collision.threshold=0")),
            "scene.json: collision.threshold: must be positive, got 0.0");
  EXPECT_EQ(error_for(with("manipulation.attach_time=-0.1")),
            "scene.json: manipulation.attach_time: must not be negative, got -0.1");
}

TEST(Scene, PinsOffTheGrid) {
  EXPECT_EQ(error_for(with("pins=[[0, 0], [4, 0]]")),
            "scene.json: pins[1]: [4, 0] is off the 4 x 5 grid");
  EXPECT_EQ(error_for(with("pins=[[0]]")), "scene.json: pins[0]: expected [row, col] integers, got [0]");
  EXPECT_EQ(error_for(with("pins=[[0, 0], [1, 2], [0, 0]]")), "scene.json: pins[2]: repeats pins[0]");
}

TEST(Scene, AnErrorInsideAnOverriddenValueFindsItsOverride) {
  const std::vector<std::string> overrides = {"cloth.k_structural=5", "pins=[[0, 0, 1]]",
                                              "cloth.k=1", "cloth.k_structural=6"};
  EXPECT_EQ(override_holding(overrides, "cloth.k_structural"), 3u);  // the last one wins
  EXPECT_EQ(override_holding(overrides, "pins[0]"), 1u);
  EXPECT_EQ(override_holding(overrides, "cloth.k"), 2u);
  EXPECT_FALSE(override_holding(overrides, "cloth.k_shear").has_value());
  EXPECT_FALSE(override_holding(overrides, "cloth").has_value());
  EXPECT_FALSE(override_holding({}, "duration").has_value());
  // An override that made the object an error is about (a: unknown key) is behind it.
  EXPECT_EQ(override_behind({"duration=1", "a.b=1"}, "a"), 1u);
  EXPECT_EQ(override_behind(overrides, "cloth.k_structural"), 3u);
}

// A scene file that is no object is named as such, before an override finds it not an object
// (a message that blamed --set would name no file).
TEST(Scene, AFileThatIsNoObjectIsNamedBeforeTheOverrides) {
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "array.json";
  std::ofstream(file) << "[1, 2, 3]";
  EXPECT_EQ(testing::input_error_message([&] {
              with_command_line_overrides(file.string(), {"duration=0.1"},
                                          [](const Scene&) { return 0; });
            }),
            file.string() + ": expected a JSON object, got array");
}

TEST(Scene, DirectionsMustBeOrthogonalUnitVectors) {
  EXPECT_EQ(error_for(with("cloth.col_dir=[2, 0, 0]")),
            "scene.json: cloth.col_dir: must be a unit vector, has length 2.000000");
  EXPECT_EQ(error_for(with("cloth.row_dir=[1, 0, 0]")),
            "scene.json: cloth.row_dir: must be orthogonal to cloth.col_dir");
}

TEST(Scene, OverridesCreatePathsAndParseJsonElseString) {
  nlohmann::json scene = valid_scene();
  apply_override(scene, "integrator.name=arkode-dirk");
  apply_override(scene, "integrator.dt=0.01");
  apply_override(scene, "output.energy_interval=0");
  EXPECT_EQ(scene["integrator"]["name"], "arkode-dirk");
  EXPECT_EQ(scene["integrator"]["dt"], 0.01);
  EXPECT_EQ(scene["output"]["energy_interval"], 0);
  EXPECT_THROW(apply_override(scene, "novalue"), InputError);
  EXPECT_THROW(apply_override(scene, "duration.x=1"), InputError);
  EXPECT_EQ(testing::input_error_message([&] { apply_override(scene, "description=\xff\xfe"); }),
            "--set: description: not valid UTF-8 text");
  // The nesting limit holds for a key path (50000 levels overflowed the stack).
  std::string deep;
  for (int k = 0; k < 64; ++k) deep += "a.";
  EXPECT_NE(testing::input_error_message([&] { apply_override(scene, deep + "b=1"); })
                .find("a key path deeper than 64 levels"),
            std::string::npos);
  nlohmann::json copy = valid_scene();
  deep.resize(deep.size() - 2);  // 63 objects and b: 64 levels, within the limit
  apply_override(copy, deep + "b=1");
}

TEST(Scene, FabricPresetDerivesMassAndSpringsAndFillsTheSceneAsRun) {
  nlohmann::json scene = valid_scene();
  scene["cloth"].erase("particle_mass");
  scene["cloth"].erase("k_structural");
  scene["cloth"]["fabric"] = "gray-interlock";
  const Scene s = parse_scene(scene, "scene.json", ".");
  // docs/fabrics.md at h = 0.02: rho_A h^2, C11 - G, G, 16 B / h^2.
  EXPECT_NEAR(s.cloth.particle_mass, 0.187 * 4e-4, 1e-15);
  EXPECT_NEAR(s.cloth.k_structural, 25.5354775 - 18.430151, 1e-9);
  EXPECT_NEAR(s.cloth.k_shear, 18.430151, 1e-9);
  EXPECT_NEAR(s.cloth.k_bending, 16.0 * 20.736428667e-6 / 4e-4, 1e-8);
  EXPECT_EQ(s.source["cloth"]["fabric"], "gray-interlock");
  EXPECT_EQ(s.source["cloth"]["k_structural"].get<double>(), s.cloth.k_structural);
  EXPECT_EQ(s.source["cloth"]["k_bending"].get<double>(), s.cloth.k_bending);
}

TEST(Scene, ExplicitClothKeysOverrideTheFabric) {
  nlohmann::json scene = with("cloth.fabric=\"11oz-black-denim\"");
  scene["cloth"]["k_bending"] = 0.5;
  const Scene s = parse_scene(scene, "scene.json", ".");
  EXPECT_EQ(s.cloth.particle_mass, 0.001);
  EXPECT_EQ(s.cloth.k_structural, 50.0);
  EXPECT_EQ(s.cloth.k_bending, 0.5);
  EXPECT_NEAR(s.cloth.k_shear, 26.693592, 1e-9) << "only the keys not given come from the fabric";
  EXPECT_EQ(s.source["cloth"]["k_structural"], 50.0);
}

TEST(Scene, AFabricValueOutOfRangeNamesTheSpacingItCameFrom) {
  nlohmann::json scene = valid_scene();
  scene["cloth"].erase("particle_mass");
  scene["cloth"].erase("k_structural");
  scene["cloth"]["fabric"] = "gray-interlock";
  scene["cloth"]["spacing"] = 1e-6;  // rho_A h^2 is below a picogram
  const std::string message = error_for(scene);
  EXPECT_EQ(message.rfind("scene.json: cloth.spacing: gives the fabric's particle_mass, which "
                          "must be at least 1e-12, got ", 0), 0u) << message;
  scene["cloth"]["particle_mass"] = 0.0;  // given in the scene: its own error
  EXPECT_EQ(error_for(scene), "scene.json: cloth.particle_mass: must be at least 1e-12, got 0.0");
}

TEST(Scene, UnknownFabricIsNamed) {
  EXPECT_EQ(error_for(with("cloth.fabric=\"velvet\"")).rfind("scene.json: cloth.fabric: unknown fabric 'velvet' (known: paper, ", 0), 0u)
      << error_for(with("cloth.fabric=\"velvet\""));
}

}  // namespace
}  // namespace drape
