// The camera path JSON reader (core/scene_io.hpp: path_from_json_text). An accepted path's every
// frame must pass core's camera validation.
#include "core/camera.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "fuzz/harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cullcheck;
  fuzz::reject_only_as<InputError>([&] {
    const CameraPath path = path_from_json_text(fuzz::bytes_of(data, size));
    fuzz::require(path.frames_per_second > 0.0, "frames_per_second > 0");
    for (std::size_t i = 0; i < path.frames.size(); ++i) {
      try {
        validate(path.frames[i], "path frame " + std::to_string(i));
      } catch (const InputError& e) {
        fuzz::crash(std::string("an accepted path holds an invalid camera: ") + e.what());
      }
    }
  });
  return 0;
}
