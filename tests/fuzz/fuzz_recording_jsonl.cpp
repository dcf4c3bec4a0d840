// libFuzzer target: the native JSON Lines recording reader (docs/input.md, docs/fuzzing.md).
#include "core/input/recording.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = drape::fuzz::input_file(data, size, "recording.jsonl");
  return drape::fuzz::accept_input_errors([&] { drape::read_drapelab_recording(file); });
}
