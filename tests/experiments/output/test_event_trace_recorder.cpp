// event_trace/ (docs/outputs.md): the frames of the window after the start at the fixed rate,
// those at step ends equal to trace.csv's in single precision, the fixed flags, and a run whose
// steps recording leaves unchanged. The windows after events: test_event_trace.py.
#include "experiments/output/event_trace_recorder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "experiments/runner/run_scene.hpp"
#include "experiments/viewer/csv_table.hpp"
#include "tests/experiments/run/run_fixtures.hpp"

namespace drape {
namespace {

namespace fs = std::filesystem;

/// A .npy file drapelab wrote: its header dictionary and its data bytes.
struct Npy {
  std::string dict, data;
  explicit Npy(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes(std::istreambuf_iterator<char>(in), {});
    const std::size_t length = static_cast<unsigned char>(bytes.at(8)) +
                               256 * static_cast<std::size_t>(static_cast<unsigned char>(bytes.at(9)));
    dict = bytes.substr(10, length);
    data = bytes.substr(10 + length);
  }
  bool has(const std::string& text) const { return dict.find(text) != std::string::npos; }
  template <class T>
  T at(std::size_t k) const {
    T value;
    std::memcpy(&value, data.data() + k * sizeof(T), sizeof(T));
    return value;
  }
};

Scene hanging(double event_trace_interval) {
  Scene scene = testing::hanging_scene(0.05);
  scene.output.event_trace_interval = event_trace_interval;
  scene.output.event_trace_window = 0.02;
  scene.output.trace_interval = 0.01;
  return scene;
}

TEST(EventTraceRecorder, TheStartsWindowAtTheFixedRateAsTheTraceHasIt) {
  const fs::path plain = fs::path(::testing::TempDir()) / "event_trace_plain";
  const fs::path traced = fs::path(::testing::TempDir()) / "event_trace_recorded";
  fs::remove_all(plain);
  fs::remove_all(traced);
  const auto a = run_scene(hanging(0.0), plain);
  const auto b = run_scene(hanging(0.0005), traced);
  EXPECT_FALSE(fs::exists(plain / "event_trace"));
  EXPECT_EQ(a.summary["steps"], b.summary["steps"]) << "recording never changes a step";
  EXPECT_EQ(a.summary["energy_final"], b.summary["energy_final"]);

  // [0, 0.02] every 0.5 ms: 41 frames, half of them inside a 1 ms step.
  const Npy t(traced / "event_trace" / "t.npy"), x(traced / "event_trace" / "x.npy");
  const Npy fixed(traced / "event_trace" / "fixed.npy");
  EXPECT_TRUE(t.has("'descr': '<f8', 'fortran_order': False, 'shape': (41,)"));
  EXPECT_TRUE(x.has("'descr': '<f4', 'fortran_order': False, 'shape': (41, 12, 3)"));
  EXPECT_TRUE(fixed.has("'descr': '|u1', 'fortran_order': False, 'shape': (41, 12)"));
  ASSERT_EQ(x.data.size(), 41u * 12 * 3 * sizeof(float));
  for (std::size_t k = 0; k < 41; ++k) EXPECT_NEAR(t.at<double>(k), 0.0005 * k, 1e-15) << k;
  EXPECT_EQ(fixed.at<std::uint8_t>(0), 1) << "the pin";
  EXPECT_EQ(fixed.at<std::uint8_t>(40 * 12 + 11), 0);

  // The frames at 0.01 s and 0.02 s are step ends: trace.csv's positions, in single precision.
  const CsvTable trace(traced / "trace.csv", {"t", "index", "x", "y", "z"});
  int compared = 0;
  for (int r = 0; r < trace.rows(); ++r) {
    const double time = trace.at(r, 0);
    if (time < 0.005 || time > 0.0205) continue;
    const auto frame = static_cast<std::size_t>(std::lround(time / 0.0005));
    const auto i = static_cast<std::size_t>(trace.at(r, 1));
    for (std::size_t a = 0; a < 3; ++a)
      EXPECT_EQ(x.at<float>((frame * 12 + i) * 3 + a), static_cast<float>(trace.at(r, 2 + a)))
          << "t " << time << ", particle " << i;
    ++compared;
  }
  EXPECT_EQ(compared, 2 * 12);
}

}  // namespace
}  // namespace drape
