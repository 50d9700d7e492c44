// Claim searches on every core (claims.hpp: search_scenes): the ledger one thread writes, whatever
// the number of threads: counts added, the lowest refuting scene's counterexample kept, the lowest
// failing scene's error raised. And a real search (ΔH's lateral step) on one and on three threads.
#include "reports/claims.hpp"

#include <gtest/gtest.h>

#include "reports/tests/synthetic_search.hpp"

#include <stdexcept>

#include "reports/delta_claims.hpp"

namespace cullcheck {
namespace {

// Scene i checks i + 1 frames; scenes 3 and 5 refute the claim (synthetic_search.hpp).
constexpr auto synthetic = testing::synthetic_search;

TEST(ClaimSearch, AnyNumberOfThreadsWritesTheLedgerOfOne) {
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    ClaimCheck c;
    c.id = "synthetic";
    search_scenes(7, threads, Shard{}, {&c}, "test", synthetic);
    EXPECT_EQ(c.frames_checked, 28u) << threads;  // 1 + 2 + ... + 7
    EXPECT_EQ(c.violations, 4u) << threads;
    EXPECT_FALSE(c.holds);
    EXPECT_EQ(c.counterexample_replay, "replay scene 3") << "the lowest refuting scene, on " << threads << " threads";
  }
}

TEST(ClaimSearch, TheLowestFailingScenesErrorIsRaised) {
  ClaimCheck c;
  EXPECT_THROW(
      {
        try {
          search_scenes(6, 3, Shard{}, {&c}, "test", [](int index, std::vector<ClaimCheck>&) {
            if (index >= 2) throw std::runtime_error("scene " + std::to_string(index));
          });
        } catch (const std::runtime_error& e) {
          EXPECT_STREQ(e.what(), "scene 2");
          throw;
        }
      },
      std::runtime_error);
}

TEST(ClaimSearch, TheOracleRunsOnOneThreadWithinAThreadedSearch) {
  oracle::OracleOptions o;
  o.sampling.threads = 4;
  EXPECT_EQ(for_one_scene(o, 2, 6).sampling.threads, 1);
  EXPECT_EQ(for_one_scene(o, 1, 6).sampling.threads, 4);
  EXPECT_EQ(for_one_scene(o, 8, 1).sampling.threads, 4) << "one scene: one search thread";
}

TEST(ClaimSearch, TheDeltaHorizonSearchIsTheSameOnOneAndThreeThreads) {
  ClaimSearchOptions options;
  options.scenes = 4;
  options.cameras_per_scene = 16;
  options.threads = 1;
  std::vector<ClaimCheck> one = check_delta_horizon_claims(options);
  options.threads = 3;
  std::vector<ClaimCheck> three = check_delta_horizon_claims(options);
  ASSERT_EQ(one.size(), 2u);
  ASSERT_EQ(three.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    nlohmann::json a = to_json(one[k]), b = to_json(three[k]);
    a.erase("search_seconds"), b.erase("search_seconds");
    EXPECT_EQ(a, b) << a.dump() << "\n" << b.dump();
  }
  // The published ΔH is refuted in the first scene (seed 1000), as the main job's ledger says.
  EXPECT_EQ(one[0].frames_checked, 324u);
  EXPECT_FALSE(one[0].holds);
  EXPECT_NE(one[0].counterexample_replay.find("--generator manhattan --seed 1000 "), std::string::npos);
}

}  // namespace
}  // namespace cullcheck
