// A property binary for property_shards_test.sh, never run as a test of its own: passing
// properties, plain tests, and one property that fails, so that the comparison of a sharded run
// with a whole one covers a shrunk counterexample (its text holds the values RapidCheck drew and
// shrank, which a changed seed would change).
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <vector>

namespace {

RC_GTEST_PROP(ShardFixture, SortingTwiceIsSortingOnce, (std::vector<int> v)) {
  std::sort(v.begin(), v.end());
  std::vector<int> again = v;
  std::sort(again.begin(), again.end());
  RC_ASSERT(again == v);
}

RC_GTEST_PROP(ShardFixture, ReversingTwiceIsTheIdentity, (std::vector<std::int64_t> v)) {
  std::vector<std::int64_t> w = v;
  std::reverse(w.begin(), w.end());
  std::reverse(w.begin(), w.end());
  RC_ASSERT(w == v);
}

// Fails: RapidCheck finds a vector whose sum passes 300 and shrinks it.
RC_GTEST_PROP(ShardFixture, SmallSumsOnly, (std::vector<std::uint8_t> v)) {
  const int sum = std::accumulate(v.begin(), v.end(), 0);
  RC_ASSERT(sum < 300);
}

RC_GTEST_PROP(ShardFixture, MaxIsAnElement, (std::vector<int> v)) {
  RC_PRE(!v.empty());
  const int m = *std::max_element(v.begin(), v.end());
  RC_ASSERT(std::find(v.begin(), v.end(), m) != v.end());
}

TEST(ShardFixture, PlainTestOne) { EXPECT_EQ(1 + 1, 2); }
TEST(ShardFixture, PlainTestTwo) { EXPECT_EQ(2 * 3, 6); }

RC_GTEST_PROP(ShardFixture, AbsoluteValuesAreNotNegative, (int x)) {
  RC_PRE(x != std::numeric_limits<int>::min());
  RC_ASSERT(std::abs(x) >= 0);
}

}  // namespace
