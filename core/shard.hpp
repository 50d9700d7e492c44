// One shard of a run split over machines (`--shard K/N`): the run's units of work (the oracle's
// checked frames, a claim search's scenes, view cells, fuzz cases, whole report sections) are
// numbered the same way in every shard, and shard K does those whose number is K modulo N.
// `cullcheck merge` joins the N shard files into the report of the unsharded run.
#pragma once

#include <cstddef>
#include <string>

namespace cullcheck {

struct Shard {
  std::size_t index = 0;  // K, from 0
  std::size_t count = 1;  // N
  bool whole() const { return count == 1; }
  bool owns(std::size_t unit) const { return unit % count == index; }
  // The units of 0 .. units - 1 this shard does.
  std::size_t share(std::size_t units) const { return units / count + (index < units % count ? 1 : 0); }
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
  friend bool operator==(const Shard&, const Shard&) = default;
};

// "K/N" with 0 <= K < N <= 10000; anything else is an InputError naming the flag.
Shard parse_shard(const std::string& text, const std::string& flag = "shard");

}  // namespace cullcheck
