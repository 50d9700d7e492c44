// The knobs of on-line image-space culling (Wang, Agarwal & Har-Peled 2001), all the user's to
// choose: the paper tunes Δ, the mask size, ρ, D, the mask levels and R (section 7.1).
#pragma once

#include <cstdint>

namespace cullcheck {

struct OnlineCullingOptions {
  int shrink_pixels = 6;            // Δ: erosion beyond the extra pixel (Fig. 12 uses 6)
  int mask_size = 256;              // s: mask pixels across the horizontal field of view
  std::uint32_t leaf_size = 16;     // ρ: most polygons in a kd-tree leaf
  double min_distance = 20.0;       // D: no occluder nearer than this (metres)
  double max_speed = 2.0;           // V: the walker's greatest speed (m/s); stamps last δ / V
  int mask_block = 2;               // b: each coarser mask pixel is the max of b x b finer ones
  int mask_levels = -1;             // coarser masks above M_0; -1: down to one pixel
  std::uint32_t occluders = 1500;   // R: occluder polygons chosen per critical frame
  bool coverage_priority = true;    // φ by coverage and distance (true) or distance only
  int coverage_grid = 16;           // image cells each way for the coverage counts
  // Draw the ground plane z = 0 into the occluders' depth image (our addition: the paper's models
  // hold buildings only; without the ground, erosion eats the foot of every facade).
  bool ground_occluder = true;
  double critical_turn = 0.15;      // radians the view may turn from the critical frame's (the masks
                                    // reach this far beyond the frustum)
  // Misdrawn pixels per frame the method claims at most (the CI gate's budget for it).
  std::uint64_t pixel_budget = 200;
};

}  // namespace cullcheck
