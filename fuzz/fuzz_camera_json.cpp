// The camera JSON reader (core/scene_io.hpp: camera_from_json_text). An accepted camera must pass
// core's own validation (core/camera.hpp: validate) and survive its writer and reader again.
#include "core/camera.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "fuzz/harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cullcheck;
  fuzz::reject_only_as<InputError>([&] {
    const Camera camera = camera_from_json_text(fuzz::bytes_of(data, size));
    try {
      validate(camera, "accepted camera");
      camera_from_json_text(camera_to_json_text(camera));
    } catch (const InputError& e) {
      fuzz::crash(std::string("an accepted camera does not survive validation or its own round trip: ") + e.what());
    }
  });
  return 0;
}
