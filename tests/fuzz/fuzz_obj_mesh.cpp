// libFuzzer target: an OBJ dummy source, read and sliced as a scene's "mesh" dummy would be
// (docs/dress_form.md, docs/fuzzing.md).
#include "core/dummy/mesh_sections.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file = drape::fuzz::input_file(data, size, "dummy.obj");
  return drape::fuzz::accept_input_errors([&] {
    const drape::TriangleMesh mesh = drape::read_obj_mesh(file, 0.01);
    // Few sections and rays: each input is sliced, and a slow input is a finding of its own.
    const int sections = 4, points = 8;
    const drape::HeightRange range = drape::default_slice_range(mesh, sections);
    drape::mesh_sections(mesh, range.top, range.bottom, sections, points);
  });
}
