// The subject protocol reader (subjects/protocol.hpp): what a subject program sends, one JSON line
// at a time - its ready line in the handshake and its visible line for a frame. A rejection must
// be a SubjectError; an accepted visible set must be sorted, unique and within the scene's ids.
#include <algorithm>

#include "fuzz/harness.hpp"
#include "subjects/protocol.hpp"
#include "subjects/subject_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cullcheck;
  const std::string line = fuzz::bytes_of(data, size);
  fuzz::reject_only_as<SubjectError>([&] {
    const protocol::Ready ready = protocol::parse_ready(line, "fuzzed subject");
    fuzz::require(ready.claim.conservative != ready.claim.pixel_error_budget.has_value(),
                  "a budget exactly when the claim is approximate");
  });
  // The scene's ids (sorted) and the frame cullcheck expects; the seed corpus uses the same.
  static const std::vector<ObjectId> known = {0, 1, 2, 3, 5, 8, 13, 21, 4294967295u};
  for (const std::size_t frame : {std::size_t{0}, std::size_t{3}}) {
    fuzz::reject_only_as<SubjectError>([&] {
      const protocol::Visible visible = protocol::parse_visible(line, "fuzzed subject", frame, known);
      fuzz::require(visible.frame == frame, "the frame asked for");
      fuzz::require(std::is_sorted(visible.ids.begin(), visible.ids.end()) &&
                        std::adjacent_find(visible.ids.begin(), visible.ids.end()) == visible.ids.end(),
                    "ids sorted and unique");
      for (ObjectId id : visible.ids) fuzz::require(std::binary_search(known.begin(), known.end(), id), "ids known");
      fuzz::require(!visible.cull_ms || *visible.cull_ms >= 0.0, "cull_ms >= 0");
    });
  }
  return 0;
}
