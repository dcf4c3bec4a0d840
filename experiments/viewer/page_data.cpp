#include "experiments/viewer/page_data.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace drape {

namespace {

constexpr int quantum_max = 32767;
constexpr size_t energy_points = 2000;

// Shortest JSON form of a value kept to `digits` significant digits.
double significant(double x, int digits) {
  if (x == 0.0 || !std::isfinite(x)) return std::isfinite(x) ? x : 0.0;
  const double scale =
      std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::fabs(x)))));
  return std::round(x * scale) / scale;
}

nlohmann::json rounded(const std::vector<double>& values, const std::vector<size_t>& keep,
                       int digits) {
  nlohmann::json out = nlohmann::json::array();
  for (const size_t i : keep) out.push_back(significant(values[i], digits));
  return out;
}

// Object particle and hand coordinates to 0.1 mm, enough for a picture, a third of the text.
template <class Real>
nlohmann::json millimetric(const std::vector<Real>& values) {
  nlohmann::json out = nlohmann::json::array();
  for (const Real v : values) out.push_back(std::round(static_cast<double>(v) * 1e4) / 1e4);
  return out;
}

std::string base64_of_int16(const std::vector<int16_t>& values) {
  // Little-endian, as JavaScript's Int16Array reads it on every platform browsers run on.
  std::vector<unsigned char> bytes(2 * values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    const auto u = static_cast<uint16_t>(values[i]);
    bytes[2 * i] = static_cast<unsigned char>(u & 0xff);
    bytes[2 * i + 1] = static_cast<unsigned char>(u >> 8);
  }
  return base64_encode(bytes.data(), bytes.size());
}

nlohmann::json hands_json(const std::vector<ViewerHand>& hands) {
  nlohmann::json out = nlohmann::json::array();
  for (const ViewerHand& h : hands) {
    std::vector<size_t> all(h.t.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = i;
    out.push_back({{"name", h.name},
                   {"t", rounded(h.t, all, 9)},
                   {"available", h.available},
                   {"positions", millimetric(h.positions)},
                   {"candidate", h.candidate},
                   {"held", h.held}});
  }
  return out;
}

}  // namespace

std::string base64_encode(const unsigned char* bytes, size_t size) {
  static constexpr char alphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (size_t i = 0; i < size; i += 3) {
    const uint32_t b0 = bytes[i];
    const uint32_t b1 = i + 1 < size ? bytes[i + 1] : 0;
    const uint32_t b2 = i + 2 < size ? bytes[i + 2] : 0;
    const uint32_t word = (b0 << 16) | (b1 << 8) | b2;
    out += alphabet[(word >> 18) & 63];
    out += alphabet[(word >> 12) & 63];
    out += i + 1 < size ? alphabet[(word >> 6) & 63] : '=';
    out += i + 2 < size ? alphabet[word & 63] : '=';
  }
  return out;
}

QuantisedPositions quantise_frames(const std::vector<ViewerFrame>& frames) {
  QuantisedPositions q;
  float low[3], high[3];
  for (int k = 0; k < 3; ++k) {
    low[k] = std::numeric_limits<float>::max();
    high[k] = std::numeric_limits<float>::lowest();
  }
  for (const ViewerFrame& f : frames)
    for (size_t i = 0; i < f.positions.size(); ++i) {
      low[i % 3] = std::min(low[i % 3], f.positions[i]);
      high[i % 3] = std::max(high[i % 3], f.positions[i]);
    }
  double half = 0.0;
  for (int k = 0; k < 3; ++k) {
    if (low[k] > high[k]) low[k] = high[k] = 0.0f;  // no frames
    q.centre[k] = 0.5f * (low[k] + high[k]);
    half = std::max(half, 0.5 * (static_cast<double>(high[k]) - low[k]));
  }
  // A tiny margin so that rounding the centre to float never pushes an extreme past the range.
  q.step = half > 0.0 ? half * (1.0 + 1e-6) / quantum_max : 1e-6;
  for (const ViewerFrame& f : frames)
    for (size_t i = 0; i < f.positions.size(); ++i) {
      const double u = (f.positions[i] - q.centre[i % 3]) / q.step;
      q.values.push_back(static_cast<int16_t>(std::clamp(
          std::lround(u), static_cast<long>(-quantum_max), static_cast<long>(quantum_max))));
    }
  return q;
}

std::vector<size_t> decimate_min_max(const std::vector<double>& values, size_t max_points) {
  const size_t n = values.size();
  std::vector<size_t> keep;
  if (n <= max_points || max_points < 4) {
    for (size_t i = 0; i < n; ++i) keep.push_back(i);
    return keep;
  }
  const size_t buckets = max_points / 2 - 1;
  keep.push_back(0);
  for (size_t b = 0; b < buckets; ++b) {
    const size_t begin = 1 + (n - 2) * b / buckets, end = 1 + (n - 2) * (b + 1) / buckets;
    if (begin >= end) continue;
    const auto first = values.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = values.begin() + static_cast<std::ptrdiff_t>(end);
    const size_t lo = static_cast<size_t>(std::min_element(first, last) - values.begin());
    const size_t hi = static_cast<size_t>(std::max_element(first, last) - values.begin());
    keep.push_back(std::min(lo, hi));
    if (hi != lo) keep.push_back(std::max(lo, hi));
  }
  keep.push_back(n - 1);
  return keep;
}

nlohmann::json dummy_page_json(int sections, int points, const std::vector<double>& positions) {
  return {{"sections", sections}, {"points", points}, {"positions", millimetric(positions)}};
}

nlohmann::json page_data(const ViewerRun& run) {
  const QuantisedPositions q = quantise_frames(run.frames);
  nlohmann::json times = nlohmann::json::array(), events = nlohmann::json::array();
  nlohmann::json fixed = nlohmann::json::array();
  const std::vector<int>* previous = nullptr;
  for (size_t f = 0; f < run.frames.size(); ++f) {
    const ViewerFrame& frame = run.frames[f];
    times.push_back(significant(frame.t, 12));
    if (frame.event) events.push_back(f);
    // The fixed set changes only at events: store it where it changes.
    if (!previous || *previous != frame.fixed)
      fixed.push_back({{"frame", f}, {"particles", frame.fixed}});
    previous = &frame.fixed;
  }
  const std::vector<size_t> keep = decimate_min_max(run.energy_kinetic, energy_points);
  const nlohmann::json& s = run.summary;
  return {
      {"name", run.name},
      {"source", run.source},
      {"status", s.value("status", std::string("?"))},
      {"integrator", s.value("integrator", std::string("?"))},
      {"table", s.contains("table") && s["table"].is_string() ? s["table"] : nlohmann::json("")},
      {"dt", s.contains("dt") ? s["dt"] : nlohmann::json(nullptr)},
      {"adaptive", s.value("adaptive", false)},
      {"duration", s.value("duration", 0.0)},
      {"sim_time", s.value("sim_time", 0.0)},
      // Why a run diverged or failed: the page says so beside its last written frame.
      {"reason",
       s.contains("reason") && s["reason"].is_string() ? s["reason"] : nlohmann::json("")},
      {"description", s.contains("scene") ? s["scene"].value("description", std::string()) : ""},
      {"rows", run.rows},
      {"cols", run.cols},
      {"pins", s["scene"].value("pins", nlohmann::json::array())},
      {"events", s["events"]},
      {"frames",
       {{"count", run.frames.size()},
        {"times", times},
        {"event_frames", events},
        {"centre", {q.centre[0], q.centre[1], q.centre[2]}},
        {"step", q.step},
        {"positions", base64_of_int16(q.values)},
        {"fixed", fixed}}},
      {"dummy", dummy_page_json(run.dummy_sections, run.dummy_points,
                                {run.dummy_positions.begin(), run.dummy_positions.end()})},
      {"hands", hands_json(run.hands)},
      {"energy",
       {{"t", rounded(run.energy_t, keep, 9)},
        {"kinetic", rounded(run.energy_kinetic, keep, 6)},
        {"total", rounded(run.energy_total, keep, 9)}}}};
}

}  // namespace drape
