// SplitMix64 (Steele, Lea and Flood 2014): a tiny seeded PRNG written out here, rather than a
// std:: distribution, so the jittered rays are bit-identical on every standard library.
#pragma once

#include <cstdint>

namespace cullcheck::oracle {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  // The stream as it stands after `draws` calls of next(): the state only counts up, so any
  // place in it is reached at once (the oracle plans runs of stratified cells on any thread).
  static SplitMix64 at(std::uint64_t seed, std::uint64_t draws) { return SplitMix64(seed + draws * kGamma); }
  std::uint64_t next() {
    std::uint64_t z = (state_ += kGamma);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1): the top 53 bits, exactly representable.
  double unit() { return double(next() >> 11) * 0x1.0p-53; }

 private:
  static constexpr std::uint64_t kGamma = 0x9e3779b97f4a7c15ULL;
  std::uint64_t state_;
};

}  // namespace cullcheck::oracle
