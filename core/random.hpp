// A small portable pseudo-random generator for the procedural cities, camera paths and simulations.
//
// Why not <random>'s distributions: std::uniform_real_distribution and friends are specified
// only loosely, so libstdc++, libc++ and MSVC turn the same engine output into different
// numbers. cullcheck promises that one seed replays one run on any machine (design: "Replay
// from a seed"), so every distribution here is written out by hand over plain 64-bit integer
// arithmetic and IEEE double operations that are exactly specified.
//
// Engine: xoshiro256** (Blackman & Vigna), state seeded by SplitMix64 as its authors recommend.
#pragma once

#include <cstdint>

namespace cullcheck {

// SplitMix64 step: also used on its own to derive independent streams from (seed, tags).
constexpr std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Folds b into the hash a (SplitMix64 of a ^ b·φ): the digests of runs and graphs, and draws keyed
// by a message's identity, are chains of it.
constexpr std::uint64_t hash_mix(std::uint64_t a, std::uint64_t b) {
  std::uint64_t s = a ^ (b * 0x9E3779B97F4A7C15ULL);
  return splitmix64(s);
}

class Random {
 public:
  explicit constexpr Random(std::uint64_t seed) {
    std::uint64_t sm = seed;
    for (auto& word : s_) word = splitmix64(sm);
  }

  // An independent stream for one part of a scene (a block, a kiosk set, ...). Keying a stream
  // by its position rather than by draw order keeps a block's buildings the same when the city
  // around it grows or shrinks, so a shrunk RapidCheck counterexample still resembles the
  // original failure.
  static constexpr Random stream(std::uint64_t seed, std::uint64_t tag, std::uint64_t a = 0, std::uint64_t b = 0) {
    std::uint64_t h = seed;
    splitmix64(h);
    h ^= tag * 0xD6E8FEB86659FD93ULL;
    splitmix64(h);
    h ^= a * 0x9E3779B97F4A7C15ULL;
    splitmix64(h);
    h ^= b * 0xC2B2AE3D27D4EB4FULL;
    return Random(splitmix64(h));
  }

  constexpr std::uint64_t next_u64() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  // Uniform in [0, 1) on the 2^-53 grid: exact conversion of a 53-bit integer.
  constexpr double uniform01() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

  // Uniform in [lo, hi) (hi itself only through rounding); lo when lo == hi.
  constexpr double uniform_real(double lo, double hi) { return lo + (hi - lo) * uniform01(); }

  // Uniform integer in [lo, hi] inclusive, without modulo bias (rejection of the short tail).
  constexpr std::int64_t uniform_int(std::int64_t lo, std::int64_t hi) {
    if (hi <= lo) return lo;
    const std::uint64_t span = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo);
    if (span == ~0ULL) return static_cast<std::int64_t>(next_u64());
    const std::uint64_t range = span + 1;
    const std::uint64_t limit = ~0ULL - (~0ULL % range);  // largest multiple of range, exclusive
    std::uint64_t x = next_u64();
    while (x >= limit) x = next_u64();
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(lo) + x % range);
  }

  // True with probability p (p <= 0 never, p >= 1 always).
  constexpr bool bernoulli(double p) { return uniform01() < p; }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4]{};
};

}  // namespace cullcheck
