#include "reports/frustum_claims.hpp"

#include <chrono>

#include "core/elapsed.hpp"
#include "reports/fuzzing.hpp"

namespace cullcheck {
namespace {

struct RangeClaim {
  const char* method;
  const char* id;
  const char* source;
  const char* statement;
};

const RangeClaim kRangeClaims[] = {
    {"rdt", "sunar-rdt-outside-only", "Sunar, Zin & Sembok, range detection technique (Eq. 3-10, the three states)",
     "range detection drops only objects outside the view frustum: an object is culled when its centre is behind the "
     "eye, when its bounding sphere lies beyond a range widened by its radius, or when all eight corners of its box lie "
     "outside the ranges (OUTSIDE; INTERSECT is taken as INSIDE)"},
    {"rdt_corrected", "cullcheck-rdt-corrected", "cullcheck (engine/frustum/range_detection.hpp)",
     "the same ranges made sound: no front test beyond the sphere's, the sphere's side ranges widened by r / cos of the "
     "half angle, a box culled only when its eight corners are beyond the same one range"},
    {"radar_frustum", "placeres-radar-frustum", "Placeres's radar approach (Game Programming Gems 5), as Sunar et al. compare it",
     "bounding spheres tested against the camera-space ranges (widened by r / cos of the half angle at the sides) drop "
     "only objects outside the view frustum"},
};

}  // namespace

std::vector<ClaimCheck> check_frustum_range_claims(const ClaimSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<ClaimCheck> claims;
  for (const RangeClaim& r : kRangeClaims) {
    ClaimCheck c;
    c.id = r.id;
    c.source = r.source;
    c.statement = r.statement;
    c.method = r.method;
    claims.push_back(std::move(c));
  }
  std::vector<ClaimCheck*> pointers;
  for (ClaimCheck& c : claims) pointers.push_back(&c);
  const int count = static_cast<int>(claims.size());
  // One fuzz run per method, on one thread: RapidCheck's runs share its global configuration.
  search_scenes(count, 1, options.shard, pointers, "claims search: frustum culling by ranges (fuzzed)",
                [&](int index, std::vector<ClaimCheck>& partial) {
    FuzzOptions fuzz;
    fuzz.methods = {kRangeClaims[index].method};
    fuzz.budget = std::max(1, options.scenes * options.cameras_per_scene);
    fuzz.seed = options.seed;
    fuzz.sampling = options.sampling;
    fuzz.pixels = false;
    fuzz.hold_conservative = true;
    const FuzzResult result = fuzz_subject(fuzz);
    ClaimCheck& c = partial[static_cast<std::size_t>(index)];
    const auto checked = result.checked_frames.find(c.method);
    c.frames_checked = checked == result.checked_frames.end() ? 0 : checked->second;
    if (!result.failure) return;
    const FuzzFailure& f = *result.failure;
    c.holds = false;
    for (const MethodRun& run : f.verification.runs) c.violations += run.violation_count;
    for (const MethodRun& run : f.verification.runs)
      if (!run.violations.empty() && c.counterexample_replay.empty()) c.counterexample_replay = run.violations.front().replay;
    c.counterexample_detail = f.message + " after " + std::to_string(result.cases) + " cases, shrunk to " + std::to_string(f.objects) +
                              " object(s) and " + std::to_string(f.minimal.path.frames.size()) + " frame(s) of a " + f.minimal.kind +
                              " path (from " + std::to_string(f.first_objects) + " and " + std::to_string(f.first_frames) + ")";
  });
  const double seconds = seconds_since(start);
  for (ClaimCheck& c : claims) c.search_seconds = seconds;
  return claims;
}

}  // namespace cullcheck
