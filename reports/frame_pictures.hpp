// The pictures of one frame of a failure (a fuzzer's counterexample, `gate --pictures`): the
// top-down map (objects by class, the view volume, the missed objects in red with their witness
// rays) and the frame's image (the full scene's id buffer, misdrawn pixels in red), both PNG.
#pragma once

#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "oracle/oracle.hpp"

namespace cullcheck {

struct FramePictures {
  std::string map, image;          // the files written
  std::vector<ObjectId> seen;      // what the oracle saw (ray sampling and pixels)
  std::vector<ObjectId> missed;    // seen but not in the PVS
  std::uint64_t misdrawn_pixels = 0;
};

// Writes DIR/<stem>map.png and DIR/<stem>frame.png for `camera` and the method's `pvs`.
FramePictures write_frame_pictures(const Scene& scene, const Camera& camera, const std::vector<ObjectId>& pvs,
                                   const oracle::OracleOptions& options, const std::string& dir, const std::string& stem = "",
                                   int map_size_px = 800);

}  // namespace cullcheck
