// libFuzzer target: a scene file of arbitrary text through load_scene (JSON reader, parse_scene,
// the dummy and input it names) (docs/fuzzing.md).
#include "core/scene/scene.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = drape::fuzz::input_file(data, size, "scene.json");
  return drape::fuzz::accept_input_errors([&] { drape::load_scene(file); });
}
