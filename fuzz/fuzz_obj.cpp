// The OBJ reader (core/formats/mesh_formats.hpp: read_obj), y up and z up. An accepted scene must
// hold the scene invariants.
#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "fuzz/harness.hpp"
#include "fuzz/scene_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cullcheck;
  const std::string path = fuzz::scratch_file("input.obj", data, size);
  for (const formats::UpAxis up : {formats::UpAxis::z, formats::UpAxis::y}) {
    fuzz::reject_only_as<InputError>([&] {
      formats::ImportOptions options;
      options.obj_up = up;
      formats::ImportReport report;
      fuzz::check_scene(formats::read_obj(path, options, &report));
      fuzz::require(report.objects == report.prisms_detected + report.prisms_given + report.meshes_kept,
                    "every imported object is counted once");
    });
  }
  return 0;
}
