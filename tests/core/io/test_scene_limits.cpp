// The bounds every scene value is checked against before anything is built (docs/scene.md,
// Limits): counts in 64 bits, products that would overflow, intervals that could not advance
// time, each refused naming the field and the limit, the limits themselves accepted.
#include "core/io/scene_limits.hpp"

#include <gtest/gtest.h>

#include "tests/core/scene/scene_fixtures.hpp"

namespace drape {
namespace {

using testing::error_for;
using testing::with;

TEST(SceneLimits, ClothSizeIsCountedIn64BitsAndBounded) {
  // 46341^2 overflows an int; 20000^2 fits one but not in memory.
  EXPECT_EQ(error_for(with("cloth.rows=46341", "cloth.cols=46341")),
            "scene.json: cloth.cols: rows x cols = 2147488281 particles, more than the limit 4000000");
  EXPECT_EQ(error_for(with("cloth.rows=20000", "cloth.cols=20000")),
            "scene.json: cloth.cols: rows x cols = 400000000 particles, more than the limit 4000000");
  EXPECT_EQ(error_for(with("cloth.rows=4294967297")),
            "scene.json: cloth.rows: must be an integer from 1 to 4000000, got 4294967297");
  EXPECT_EQ(error_for(with("cloth.rows=2.5")), "scene.json: cloth.rows: expected an integer, got 2.5");
}

// At a spacing of 1e-17 m every particle would start at one point and the run end `ok`; a mass
// of 1e-300 with k = 1e12 gives an infinite frequency.
TEST(SceneLimits, SpacingAndMassTooSmallForTheModelAreRefused) {
  EXPECT_EQ(error_for(with("cloth.spacing=1e-17")),
            "scene.json: cloth.spacing: must be at least 1e-06, got 1e-17");
  EXPECT_EQ(error_for(with("cloth.spacing=1e-4", "cloth.origin=[0, 1e6, 0]")),
            "scene.json: cloth.spacing: must be at least 2^-30 of cloth.origin's largest "
            "coordinate (0.000931323 m) there, got 0.0001");
  EXPECT_EQ(error_for(with("cloth.particle_mass=1e-300")),
            "scene.json: cloth.particle_mass: must be at least 1e-12, got 1e-300");
  // The limits themselves are accepted.
  EXPECT_EQ(error_for(with("cloth.spacing=1e-6", "cloth.particle_mass=1e-12")), "no error");
}

TEST(SceneLimits, PinsAreComparedBeforeNarrowing) {
  EXPECT_EQ(error_for(with("pins=[[4294967296, 0]]")),
            "scene.json: pins[0]: [4294967296, 0] is off the 4 x 5 grid");
  EXPECT_EQ(error_for(with("manipulation.release=[0, 18446744073709551615]")),
            "scene.json: manipulation.release: expected [row, col] integers, got [0, "
            "18446744073709551615]");
}

TEST(SceneLimits, ValuesWhoseProductsOverflowAreRefused) {
  EXPECT_EQ(error_for(with("cloth.k_structural=1e308")),
            "scene.json: cloth.k_structural: must be at most 1000000000000.0, got 1e+308");
  EXPECT_EQ(error_for(with("cloth.spacing=1e308")),
            "scene.json: cloth.spacing: must be at most 1000.0, got 1e+308");
  EXPECT_EQ(error_for(with("collision.stiffness=1e300")),
            "scene.json: collision.stiffness: must be at most 1000000000000.0, got 1e+300");
  EXPECT_EQ(error_for(with("cloth.origin=[0, 1e300, 0]")),
            "scene.json: cloth.origin: must be within +-1000000.0");
  EXPECT_EQ(error_for(with("gravity=[0, -1e200, 0]")),
            "scene.json: gravity: must be within +-1000.0");
  EXPECT_EQ(error_for(with("duration=1e300")),
            "scene.json: duration: must be at most 1000000.0, got 1e+300");
  // A fraction of the spacing: 1e6 of it started a run at 10^6 m/s, 1e300 diverged at once.
  EXPECT_EQ(error_for(with("perturbation.position=1e6")),
            "scene.json: perturbation.position: must be at most 0.5, got 1000000.0");
  EXPECT_EQ(error_for(with("perturbation.position=1e300")),
            "scene.json: perturbation.position: must be at most 0.5, got 1e+300");
  EXPECT_EQ(error_for(with("perturbation.position=0.5")), "no error");
  // A hard start: a spring stretched by -1 has no length, one stretched past half is another
  // cloth; velocities beyond 100 m/s are no draping start.
  EXPECT_EQ(error_for(with("perturbation.stretch=-1")),
            "scene.json: perturbation.stretch: must be within +-0.5");
  EXPECT_EQ(error_for(with("perturbation.stretch=0.6")),
            "scene.json: perturbation.stretch: must be within +-0.5");
  EXPECT_EQ(error_for(with("perturbation.stretch=\"1%\"")),
            "scene.json: perturbation.stretch: expected a number, got string");
  EXPECT_EQ(error_for(with("perturbation.stretch=-0.5", "perturbation.velocity=100")), "no error");
  EXPECT_EQ(error_for(with("perturbation.velocity=-0.5")),
            "scene.json: perturbation.velocity: must not be negative, got -0.5");
  EXPECT_EQ(error_for(with("perturbation.velocity=1e300")),
            "scene.json: perturbation.velocity: must be at most 100.0, got 1e+300");
}

TEST(SceneLimits, OutputIntervalsMustAdvanceTimeAndBoundTheFiles) {
  EXPECT_EQ(error_for(with("output.energy_interval=1e-300")),
            "scene.json: output.energy_interval: too small to advance time over duration 0.5 s "
            "(at least duration x 2^-50)");
  EXPECT_EQ(error_for(with("output.trace_interval=1e-8")),
            "scene.json: output.trace_interval: would write 1000000020.0 rows (particles x "
            "frames), more than 1000000000.0");
  EXPECT_EQ(error_for(with("output.vtk_interval=0")), "no error");
  EXPECT_EQ(error_for(with("output.event_trace_interval=1e-8")),
            "scene.json: output.event_trace_interval: would write 1000000020.0 rows (particles x "
            "frames), more than 1000000000.0");
  EXPECT_EQ(error_for(with("output.event_trace_window=-1")),
            "scene.json: output.event_trace_window: must be positive, got -1.0");
  EXPECT_EQ(error_for(with("output.event_trace_window=1e300")),
            "scene.json: output.event_trace_window: must be at most 1000000.0, got 1e+300");
  EXPECT_EQ(error_for(with("output.event_trace_windw=0.1")),
            "scene.json: output.event_trace_windw: unknown key");
}

TEST(SceneLimits, HugeOverrideValuesAreShortenedInTheMessage) {
  const std::string message =
      error_for(with("cloth.rows=\"" + std::string(50'000'000, 'x') + "\""));
  EXPECT_EQ(message.rfind("scene.json: cloth.rows: expected an integer, got \"xxx", 0), 0u);
  EXPECT_LT(message.size(), 300u);
}

}  // namespace
}  // namespace drape
