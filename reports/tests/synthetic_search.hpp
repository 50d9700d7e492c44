// A claim search without scenes, for tests of search_scenes and of its shards: scene i checks
// i + 1 frames; scenes 3 and 5 refute the claim, two violations each.
#pragma once

#include <string>
#include <vector>

#include "reports/claims.hpp"

namespace cullcheck::testing {

inline void synthetic_search(int index, std::vector<ClaimCheck>& partial) {
  partial[0].frames_checked += std::uint64_t(index) + 1;
  if (index == 3 || index == 5) {
    partial[0].violations += 2;
    partial[0].holds = false;
    partial[0].counterexample_replay = "replay scene " + std::to_string(index);
  }
}

}  // namespace cullcheck::testing
