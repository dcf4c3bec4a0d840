#pragma once
// The live mode's page (docs/live.md).
#include <string>

namespace drape {

/// The HTML page `drapelab live` serves at "/": viewer_scene.js's 3-D scene and three.js
/// inlined with live_main.js, which follows GET /events and posts keys and hands. `scene_json`
/// is LiveSession::scene_json() (grid, pins, dress form, whether the hands are live).
std::string live_page(const std::string& scene_json);

}  // namespace drape
