// The cached collision query equals the grid query exactly, however the particles move.
#include <gtest/gtest.h>
#include <random>

#include "core/dummy/contact_finder.hpp"
#include "core/dummy/dummy_sources.hpp"

namespace drape {
namespace {

TEST(ContactFinder, EqualsTheGridQueryAlongRandomWalks) {
  const auto dummy = std::make_shared<const Dummy>(
      make_dummy(nlohmann::json{{"builtin", "dress-form"}}, "test", "dummy", "."));
  const double delta = 0.012;
  const int walkers = 200;
  ContactFinder finder(dummy, delta, walkers);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Walkers start near the front surface and move by steps from 0.1 mm to 2 cm, so lists are
  // reused, rebuilt, and jumped far past.
  std::vector<Vec3> x(walkers);
  for (int w = 0; w < walkers; ++w) {
    const double y = 1.05 + 0.2 * u(rng), theta = 1.5 * u(rng);
    const Eigen::Vector2d axis = dummy->axis_at(y);
    const double r = dummy->surface_radius(y, theta) + 0.01 * u(rng);
    x[w] = Vec3(axis.x() + r * std::sin(theta), y, axis.y() + r * std::cos(theta));
  }
  int hits = 0;
  for (int step = 0; step < 300; ++step) {
    const double size = step % 50 == 49 ? 0.02 : 1e-4 * (1 + step % 7);
    for (int w = 0; w < walkers; ++w) {
      x[w] += size * Vec3(u(rng), u(rng), u(rng));
      const NearestObjectParticle cached = finder.nearest(w, x[w]);
      const NearestObjectParticle grid = dummy->nearest_within(x[w], delta);
      ASSERT_EQ(cached.index, grid.index) << "step " << step << " walker " << w;
      if (grid.index >= 0) {
        ASSERT_EQ(cached.distance, grid.distance);
        ++hits;
      }
    }
  }
  EXPECT_GT(hits, 10000) << "most queries are in contact";
}

}  // namespace
}  // namespace drape
