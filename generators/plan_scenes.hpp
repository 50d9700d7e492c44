// Plan-view scenes for exact 2D visibility (the polar diagram's tests and benchmarks).
//
// slot_city: buildings in a grid of square slots on a half-metre grid: rectangles flush with
// their slot's sides (so neighbours share walls, run collinear and meet in T-junctions), L and U
// shapes (non-convex, with pockets to see into) and stars (non-convex, generic coordinates).
// An eye on the half-metre grid stands on many walls' supporting lines.
//
// star_block_city: the paper's experimental city in kind (Ortega et al., section 5: 600
// non-convex buildings, 45,000 vertices): one star-shaped footprint per block of a street grid.
#pragma once

#include <cstdint>
#include <string>

#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"

namespace cullcheck::generators {

struct SlotCityParams {
  int slots_x = 4, slots_y = 4;
  double slot = 8.0;     // metres
  double height = 10.0;  // every building's

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("slots_x", s.slots_x), v("slots_y", s.slots_y), v("slot", s.slot), v("height", s.height);
  }
};
Scene slot_city(const SlotCityParams& p, std::uint64_t seed);
void validate(const SlotCityParams& p, const std::string& generator = "slot_city");

struct StarBlockParams {
  int count = 600;
  int vertices = 75;       // per footprint
  double block = 60.0;     // block pitch, metres
  double street = 15.0;
  double min_height = 10.0, max_height = 60.0;

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("count", s.count), v("vertices", s.vertices), v("block", s.block), v("street", s.street);
    v("min_height", s.min_height), v("max_height", s.max_height);
  }
};
Scene star_block_city(const StarBlockParams& p, std::uint64_t seed);
void validate(const StarBlockParams& p, const std::string& generator = "star_block_city");
// The paper's observer walking its city's outskirts and streets: level eyes at 1.7 m along four
// streets between rows of blocks, looking diagonally ahead (the paper's 90-degree view centred
// at 45 degrees, alternating with 135), a 45-degree vertical view.
std::vector<Camera> star_block_walk(const StarBlockParams& p, int frames);

}  // namespace cullcheck::generators
