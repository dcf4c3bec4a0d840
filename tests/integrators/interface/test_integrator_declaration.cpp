// An integrator's declaration (docs/integrators/README.md, "Adding an integrator"): each kind of
// key with its range said in words, the JSON `drapelab integrators --json` lists (the lookup by
// name: test_integrator_options.cpp).
#include "integrators/interface/integrator_declaration.hpp"

#include <gtest/gtest.h>

namespace drape {
namespace {

TEST(IntegratorDeclaration, EachKindOfKeySaysItsRangeAndDefault) {
  EXPECT_EQ(SettingKey::integer("iterations", 10, 1, 1000, "").range_text(),
            "integer in [1, 1000], default 10");
  EXPECT_EQ(SettingKey::number("omega", 0.9, 0.0, 1.0, "").range_text(),
            "number in [0, 1], default 0.9");
  EXPECT_EQ(SettingKey::number("rho", 0.5, 0.0, 1.0, "", true, true).range_text(),
            "number in (0, 1), default 0.5");
  EXPECT_EQ(SettingKey::number("k", 1e-8, 0.0, 1e12, "", true).range_text(),
            "number in (0, 1e+12], default 1e-08");
  EXPECT_EQ(SettingKey::boolean("chebyshev", true, "").range_text(), "true or false, default true");
  EXPECT_EQ(SettingKey::choice("solver", "cg", {"cg", "ldlt"}, "").range_text(),
            "one of cg, ldlt, default cg");
}

TEST(IntegratorDeclaration, KeysAreListedInOrder) {
  IntegratorDeclaration d;
  d.name = "demo";
  d.family = "optimisation";
  d.order = 2;
  d.adaptive = true;
  d.description = "a demonstration";
  d.keys = {SettingKey::integer("iterations", 10, 1, 1000, "sweeps a step"),
            SettingKey::boolean("chebyshev", false, "accelerate")};
  EXPECT_EQ(d.to_json(), nlohmann::json::parse(R"({
      "name": "demo", "family": "optimisation", "order": 2, "adaptive": true,
      "description": "a demonstration",
      "keys": [
        {"name": "iterations", "default": 10, "range": "integer in [1, 1000], default 10",
         "description": "sweeps a step"},
        {"name": "chebyshev", "default": false, "range": "true or false, default false",
         "description": "accelerate"}]})"));
}

}  // namespace
}  // namespace drape
