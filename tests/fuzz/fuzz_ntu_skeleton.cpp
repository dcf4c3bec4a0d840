// libFuzzer target: the NTU RGB+D .skeleton reader (docs/input.md, docs/fuzzing.md).
#include "core/input/kinect_readers.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = drape::fuzz::input_file(data, size, "recording.skeleton");
  return drape::fuzz::accept_input_errors([&] { drape::read_ntu_skeleton(file); });
}
