#pragma once
// The page's data: a run folder encoded compactly as JSON (docs/viewer.md, Data encoding).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/viewer/viewer_run.hpp"

namespace drape {

/// Standard base64 (RFC 4648, with padding) of a byte buffer.
std::string base64_encode(const unsigned char* bytes, size_t size);

/// Cloth positions quantised to int16 about the centre of their bounding box:
/// x = centre + step * q, q in [-32767, 32767], frame after frame, particle after particle.
struct QuantisedPositions {
  float centre[3] = {0, 0, 0};
  double step = 1.0;
  std::vector<int16_t> values;
};

/// Quantises all frames of a run with one centre and step (bounds of every frame).
QuantisedPositions quantise_frames(const std::vector<ViewerFrame>& frames);

/// Indices kept when `values` (a curve over time) is thinned to about `max_points`: the first,
/// the last, and each bucket's minimum and maximum, so an oscillation keeps its envelope.
std::vector<size_t> decimate_min_max(const std::vector<double>& values, size_t max_points);

/// The dress form as the pages draw it (viewer_scene.js): sections, points a section and xyz per
/// object particle (to 0.1 mm); shared by `drapelab view` and `drapelab live`.
nlohmann::json dummy_page_json(int sections, int points, const std::vector<double>& positions);

/// The JSON the page reads for one run (the keys are listed in docs/viewer.md).
nlohmann::json page_data(const ViewerRun& run);

}  // namespace drape
