#pragma once
// A small run shared by the tests of the run's writers: a 3 x 4 cloth hanging from one corner,
// leap-frog at 1 ms, no object.
#include <nlohmann/json.hpp>

#include "core/scene/scene.hpp"

namespace drape::testing {

inline Scene hanging_scene(double duration) {
  nlohmann::json source = nlohmann::json::parse(R"({
    "cloth": {"rows": 3, "cols": 4, "spacing": 0.02, "origin": [0, 1.4, 0],
              "particle_mass": 0.001, "k_structural": 20},
    "pins": [[0, 0]], "dummy": null,
    "integrator": {"name": "leapfrog", "dt": 0.001}})");
  source["duration"] = duration;
  return parse_scene(source, "test.json", ".");
}

}  // namespace drape::testing
