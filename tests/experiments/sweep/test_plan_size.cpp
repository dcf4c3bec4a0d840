// The size of a plan counted from its lists before expansion (docs/experiments.md, Limits): the
// product of its factors, doubled by a reference, refused above max_plan_runs naming the largest.
#include "experiments/sweep/plan_size.hpp"

#include <gtest/gtest.h>

#include "core/io/input_error.hpp"

namespace drape {
namespace {

/// `scenes` scenes, `cases` cases, a sweep of `sweep` values per key, `repeats` repeats.
Experiment plan(int scenes, int cases, std::vector<int> sweep, int repeats) {
  Experiment e;
  e.file = "e.json";
  e.scenes.assign(scenes, "scene.json");
  e.cases.resize(cases);
  for (std::size_t k = 0; k < sweep.size(); ++k)
    e.sweep.emplace_back("key" + std::to_string(k), std::vector<nlohmann::json>(sweep[k], nlohmann::json(0)));
  e.repeats = repeats;
  return e;
}

std::string field_refused(const Experiment& e) {
  try {
    check_plan_size(e);
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "e.json");
    return error.field();
  }
  return "accepted";
}

TEST(PlanSize, TheBoundIsTheProductOfTheFactors) {
  EXPECT_EQ(plan_size_bound(plan(1, 0, {}, 0)), 1.0) << "no cases, no repeats: one run";
  EXPECT_EQ(plan_size_bound(plan(2, 3, {4, 5}, 6)), 2.0 * 3 * 4 * 5 * 6);
  Experiment with_reference = plan(2, 3, {4}, 0);
  with_reference.reference = {Override{"integrator.dt", 1e-4}};
  EXPECT_EQ(plan_size_bound(with_reference), 2.0 * 2 * 3 * 4);
  // Ten keys of ten values: 10^10 runs, counted without overflow.
  EXPECT_EQ(plan_size_bound(plan(1, 0, std::vector<int>(10, 10), 0)), 1e10);
}

TEST(PlanSize, ThePlanAboveTheLimitIsRefusedNamingItsLargestFactor) {
  EXPECT_EQ(field_refused(plan(1, 1, {}, static_cast<int>(max_plan_runs))), "accepted");
  EXPECT_EQ(field_refused(plan(1, 1, {}, static_cast<int>(max_plan_runs) + 1)), "repeats");
  EXPECT_EQ(field_refused(plan(2, 1000, {}, 51)), "cases");
  EXPECT_EQ(field_refused(plan(1, 10, {100, 200}, 0)), "sweep");
  EXPECT_EQ(field_refused(plan(400, 300, {}, 0)), "scenes");
  Experiment doubled = plan(1, 1, {}, 60000);
  EXPECT_EQ(field_refused(doubled), "accepted");
  doubled.reference = {Override{"integrator.dt", 1e-4}};
  try {
    check_plan_size(doubled);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "e.json: repeats: 120000 runs with their references, more than the limit 100000");
  }
}

}  // namespace
}  // namespace drape
