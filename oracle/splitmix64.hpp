// SplitMix64 (Steele, Lea and Flood 2014): a tiny seeded PRNG written out here, rather than a
// std:: distribution, so the jittered rays are bit-identical on every standard library.
#pragma once

#include <cstdint>

namespace cullcheck::oracle {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1): the top 53 bits, exactly representable.
  double unit() { return double(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

}  // namespace cullcheck::oracle
