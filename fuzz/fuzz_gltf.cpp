// The glTF reader (core/formats/mesh_formats.hpp: read_gltf), .glb and .gltf alike (it tells them
// apart by content), with both id sources. An accepted scene must hold the scene invariants.
#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "fuzz/harness.hpp"
#include "fuzz/scene_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cullcheck;
  const std::string path = fuzz::scratch_file("input.gltf", data, size);
  for (const formats::IdSource ids : {formats::IdSource::node, formats::IdSource::mesh}) {
    fuzz::reject_only_as<InputError>([&] {
      formats::ImportOptions options;
      options.ids = ids;
      formats::ImportReport report;
      fuzz::check_scene(formats::read_gltf(path, options, &report));
      fuzz::require(report.objects == report.prisms_detected + report.prisms_given + report.meshes_kept,
                    "every imported object is counted once");
    });
  }
  return 0;
}
