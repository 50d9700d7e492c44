// On-line image-space culling measured as Wang, Agarwal & Har-Peled (2001) measured it
// (section 7), in one run:
//  - Table 1 in kind: four generated Manhattan cities of about 3.7k, 27k, 110k and 440k polygons
//    (a box building is five polygons, as in the paper's models), an 800-frame street walk each;
//    per method (view-frustum culling, OH(OS), online_is, online_is_guarded): culling time per
//    frame (median, p95; the critical frames apart), polygons sent, CR_v and CR_o (Fig. 14:
//    culled over the polygons in the frustum, and over all polygons), the sub-steps of a
//    marking (Fig. 10), and misdrawn pixels against the full scene at the camera's resolution
//    (the pixel oracle's definition: pixels whose full-scene object is not in the PVS). The
//    paper's frame rates depend on its graphics hardware: compare polygons sent and time, as
//    ratios to OH(OS) and frustum culling from the same run.
//  - Fig. 11 and 12 on the 110k city: a Δ sweep (polygons sent, time, critical frames,
//    misdrawn pixels, error frames), the misdrawn pixels per frame along the walk at Δ = 6, and
//    the error frames along a long walk (the paper: 158 of 11,558 frames at Δ = 6).
//  - Section 6 (dynamic scenes): the 800-frame walk on the 110k city again, while 1% of the
//    buildings vanish every 30 frames and the previous event's come back (1% are absent at the
//    start): time per scene event (on-line culling updates its kd-tree in place, OH(OS) is
//    rebuilt), the critical frames an occluder's deletion causes, and the misdrawn pixels.
//  - The accuracy/speed trade: for each Δ and mask size s, culling time against misdrawn pixels,
//    beside the conservative methods' time at 0 misdrawn pixels.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/method.hpp"

namespace cullcheck {

struct OnlineTableOptions {
  std::vector<int> grids = {6, 17, 33, 66};  // blocks each way of 20 lots: 3.6k, 27k, 109k, 436k polygons
  std::uint64_t seed = 1;
  int frames = 800;
  std::size_t sweep_city = 2;                // index into grids for the sweeps and the long walk
  std::vector<int> deltas = {0, 2, 4, 6, 8, 12, 16};
  std::vector<int> mask_sizes = {128, 256, 512};
  int long_frames = 10000;
  int dynamic_every = 30;                    // the dynamic walk's events (0: no dynamic walk)
  double dynamic_churn = 0.01;
  int pixel_threads = 2;
};

nlohmann::json online_culling_table(const OnlineTableOptions& options, const MethodOptions& method_options);
std::string online_culling_text(const nlohmann::json& table);

}  // namespace cullcheck
