#pragma once
// A small valid scene and the error of a scene with overrides, shared by the scene reader's tests.
#include <nlohmann/json.hpp>
#include <string>

#include "core/scene/scene.hpp"
#include "tests/support/test_support.hpp"

namespace drape::testing {

inline nlohmann::json valid_scene() {
  return nlohmann::json::parse(R"({
    "cloth": {"rows": 4, "cols": 5, "spacing": 0.02, "origin": [0, 1.4, 0.2],
              "particle_mass": 0.001, "k_structural": 50},
    "pins": [[0, 0], [0, 4]],
    "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.001},
    "duration": 0.5
  })");
}

inline std::string error_for(const nlohmann::json& scene) {
  return input_error_message([&] { parse_scene(scene, "scene.json", "."); });
}

inline nlohmann::json with(const std::string& assignment, const std::string& second = "") {
  nlohmann::json scene = valid_scene();
  apply_override(scene, assignment);
  if (!second.empty()) apply_override(scene, second);
  return scene;
}

}  // namespace drape::testing
