// libFuzzer target: the Kinect v2 CSV reader, and format detection (docs/input.md,
// docs/fuzzing.md).
#include "core/input/kinect_readers.hpp"
#include "core/input/recording.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = drape::fuzz::input_file(data, size, "recording.csv");
  drape::fuzz::accept_input_errors([&] { drape::detect_recording_format(file); });
  return drape::fuzz::accept_input_errors([&] { drape::read_kinect_v2_csv(file); });
}
