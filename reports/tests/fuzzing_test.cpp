// The fuzzer on built-in methods (the soak run): what it counts, and its claims.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/errors.hpp"
#include "reports/fuzzing.hpp"

namespace cullcheck {
namespace {

FuzzOptions soak(int budget, std::uint64_t seed) {
  FuzzOptions o;
  o.methods = conservative_method_names();
  o.budget = budget;
  o.seed = seed;
  o.pixels = false;
  o.sampling.spacing_m = 3.0;
  o.sampling.frustum_resolution = 64;
  o.sampling.threads = 1;
  return o;
}

TEST(Fuzzing, ConservativeMethodsAreTheOnesThatClaimIt) {
  const std::vector<std::string> names = conservative_method_names();
  EXPECT_EQ(names, (std::vector<std::string>{"frustum", "rdt_corrected", "radar_frustum", "oh_os_conservative", "delta_h_guarded"}));
}

// Pinned counts: the same seed draws the same cases on every machine, so a change in the case
// generator or in which frames a method skips shows here (and invalidates stored replays).
TEST(Fuzzing, SoakCountsOracleCheckedFramesPerMethod) {
  const FuzzResult r = fuzz_subject(soak(40, 1));
  ASSERT_FALSE(r.failure) << r.failure->message;
  EXPECT_TRUE(r.built_in);
  EXPECT_EQ(r.cases, 40);
  EXPECT_EQ(r.oracle_frames, 60u);
  EXPECT_EQ(r.checked_frames.at("frustum"), 60u);
  EXPECT_EQ(r.checked_frames.at("oh_os_conservative"), 47u);
  EXPECT_EQ(r.skipped_frames.at("oh_os_conservative"), 13u);
  EXPECT_EQ(r.checked_frames.at("delta_h_guarded"), 47u);
  // Frustum culling by ranges skips the orthographic frames (and would skip 360-degree ones).
  for (const char* m : {"rdt_corrected", "radar_frustum"}) {
    EXPECT_EQ(r.checked_frames.at(m), 54u) << m;
    EXPECT_EQ(r.skipped_frames.at(m), 6u) << m;
  }
  // Orthographic cameras and mesh scenes are drawn (horizon methods skip them, and say so).
  EXPECT_GT(r.kinds.at("orthographic"), 0);
  EXPECT_GT(r.scenes.at("openings"), 0);
}

TEST(Fuzzing, SoakClaimsOnePerMethodWithItsFrames) {
  const FuzzResult r = fuzz_subject(soak(10, 2));
  const std::vector<ClaimCheck> claims = fuzz_claims(r, "");
  ASSERT_EQ(claims.size(), 5u);
  for (const ClaimCheck& c : claims) {
    EXPECT_TRUE(c.holds) << c.id;
    EXPECT_EQ(c.frames_checked, r.checked_frames.at(c.method)) << c.id;
    EXPECT_EQ(c.id, c.method + "-conservative-fuzzed");
  }
}

TEST(Fuzzing, UnknownMethodIsAnInputError) {
  FuzzOptions o = soak(1, 1);
  o.methods = {"frustum", "no_such_method"};
  EXPECT_THROW(fuzz_subject(o), InputError);
  o.methods.clear();
  EXPECT_THROW(fuzz_subject(o), InputError);
}

}  // namespace
}  // namespace cullcheck
