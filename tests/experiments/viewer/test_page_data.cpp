#include <gtest/gtest.h>

#include <cmath>

#include "experiments/viewer/page_data.hpp"
#include "viewer_test_files.hpp"

namespace drape {
namespace {

TEST(PageData, Base64MatchesRfc4648) {
  const auto encode = [](const std::string& s) {
    return base64_encode(reinterpret_cast<const unsigned char*>(s.data()), s.size());
  };
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
}

TEST(PageData, QuantisedPositionsWithinHalfAStep) {
  std::vector<ViewerFrame> frames(2);
  frames[0].positions = {-0.3f, 1.0f, 0.2f, 0.5f, 1.4f, 0.25f};
  frames[1].positions = {-0.1f, 0.8f, 0.21f, 0.45f, 1.3f, 0.3f};
  const QuantisedPositions q = quantise_frames(frames);
  ASSERT_EQ(q.values.size(), 12u);
  EXPECT_NEAR(q.step, 0.4 / 32767, 1e-9);  // half the largest extent (x: 0.8 m) over 32767
  for (size_t f = 0; f < 2; ++f)
    for (size_t i = 0; i < 6; ++i)
      EXPECT_NEAR(q.centre[i % 3] + q.step * q.values[6 * f + i], frames[f].positions[i],
                  0.5 * q.step + 1e-7);
  EXPECT_EQ(*std::max_element(q.values.begin(), q.values.end()), 32767);
}

TEST(PageData, DecimationKeepsEndsAndExtremes) {
  std::vector<double> wave(10000);
  for (size_t i = 0; i < wave.size(); ++i) wave[i] = std::sin(0.01 * static_cast<double>(i));
  wave[5003] = 7.0;
  const std::vector<size_t> keep = decimate_min_max(wave, 200);
  EXPECT_LE(keep.size(), 200u);
  EXPECT_EQ(keep.front(), 0u);
  EXPECT_EQ(keep.back(), wave.size() - 1);
  EXPECT_TRUE(std::is_sorted(keep.begin(), keep.end()));
  EXPECT_NE(std::find(keep.begin(), keep.end(), 5003u), keep.end());
  EXPECT_EQ(decimate_min_max({1.0, 2.0}, 200).size(), 2u);
}

TEST(PageData, FixedSetStoredWhereItChanges) {
  const nlohmann::json data = page_data(read_viewer_run(testing::tiny_run("page_data")));
  EXPECT_EQ(data["rows"], 1);
  EXPECT_EQ(data["frames"]["count"], 2);
  EXPECT_EQ(data["frames"]["event_frames"], nlohmann::json::array({1}));
  EXPECT_EQ(data["frames"]["fixed"].size(), 2u);
  EXPECT_EQ(data["frames"]["fixed"][1]["particles"], nlohmann::json::array({0, 1}));
  // 2 frames x 2 particles x 3 coordinates x 2 bytes = 24 bytes = 32 base64 characters.
  EXPECT_EQ(data["frames"]["positions"].get<std::string>().size(), 32u);
  EXPECT_EQ(data["events"][0]["type"], "hold");
}

// A diverged run: the page gets its reason (summary.json) and its last finite frame, 0.05 s,
// not the frame of 1e300 (infinite as float) written as it diverged.
TEST(PageData, DivergedRunCarriesReasonAndLastFiniteFrame) {
  const auto dir = testing::tiny_run("page_data_diverged");
  testing::write_text(dir / "summary.json",
                      R"({"status": "diverged", "reason": "runaway: 888 m/s", "integrator":
                          "leapfrog", "dt": 0.001, "duration": 0.1, "sim_time": 0.07,
                          "events": [], "scene": {"cloth": {"rows": 1, "cols": 2}}})");
  std::ofstream(dir / "trace.csv", std::ios::app) << "0.07,0,1e300,1,0,0,0,0,1,-1,0\n"
                                                     "0.07,1,0.02,1,0,0,0,0,0,-1,0\n";
  const nlohmann::json data = page_data(read_viewer_run(dir));
  EXPECT_EQ(data["status"], "diverged");
  EXPECT_EQ(data["reason"], "runaway: 888 m/s");
  EXPECT_DOUBLE_EQ(data["sim_time"].get<double>(), 0.07);
  EXPECT_EQ(data["frames"]["count"], 2);
  EXPECT_DOUBLE_EQ(data["frames"]["times"][1].get<double>(), 0.05);
  EXPECT_EQ(page_data(read_viewer_run(testing::tiny_run("page_data_ok")))["reason"], "");
}

}  // namespace
}  // namespace drape
