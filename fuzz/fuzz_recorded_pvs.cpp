// The recorded-PVS reader (subjects/recorded_pvs.hpp): a culling system's per-frame visible sets
// as JSON lines (`cullcheck gate --pvs FILE`). A rejection must be a SubjectError; every frame of
// an accepted file must answer with ids of the scene, and an absent frame must be a SubjectError.
#include <algorithm>

#include "core/scene_io.hpp"
#include "fuzz/harness.hpp"
#include "subjects/recorded_pvs.hpp"
#include "subjects/subject_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cullcheck;
  // Ids 0, 1, 2, 3, 5 and 8 (the seed corpus names them).
  static const Scene scene = [] {
    Scene s;
    const ObjectId ids[] = {0, 1, 2, 3, 5, 8};
    for (int i = 0; i < 6; ++i) s.buildings.push_back(box_building(ids[i], 10.0 * i, 0, 10.0 * i + 5, 5, 10));
    return s;
  }();
  static const std::vector<ObjectId> known = scene.ids();
  const std::string path = fuzz::scratch_file("input.jsonl", data, size);
  fuzz::reject_only_as<SubjectError>([&] {
    RecordedPvsMethod method(scene, path, protocol::Claim{}, "");
    const Camera camera;
    for (std::size_t frame = 0; frame < 4; ++frame) {
      method.set_frame(frame, 0.0);
      fuzz::reject_only_as<SubjectError>([&] {
        const CullResult result = method.cull(camera);
        for (ObjectId id : result.pvs) fuzz::require(std::binary_search(known.begin(), known.end(), id), "ids known");
      });
    }
  });
  return 0;
}
