// The scene JSON reader (core/scene_io.hpp: scene_from_json_text). An accepted scene must hold
// the scene invariants and be writable, and what is written must read back.
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "fuzz/harness.hpp"
#include "fuzz/scene_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cullcheck;
  fuzz::reject_only_as<InputError>([&] {
    const Scene scene = scene_from_json_text(fuzz::bytes_of(data, size));
    fuzz::check_scene(scene);
    const std::string text = scene_to_json_text(scene);
    // Written coordinates are world coordinates (local + origin): they may lie beyond the
    // reader's limits when the origin does, so re-reading may reject, but only as an InputError.
    fuzz::reject_only_as<InputError>([&] { fuzz::check_scene(scene_from_json_text(text)); });
  });
  return 0;
}
