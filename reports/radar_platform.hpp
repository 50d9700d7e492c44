// The radar on a moving platform (thesis ch. 3.3): a vehicle drives east through a terrain's
// centre and the radar turns once per position. Each rotation's echo recomputed from scratch
// (the conservative rule) against a region echo (engine/radar/region_echo.hpp) reused for
// every rotation while the vehicle stays within `radius` of the region's centre, placed
// `radius` ahead of the vehicle so that it drives the disc's diameter: how much time the reuse
// saves, how many more triangles it sends, and the oracle's word on both at sampled rotations.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/terrain.hpp"

namespace cullcheck {

struct PlatformOptions {
  int positions = 50;       // rotations
  double step = 40.0;       // metres driven per rotation (20 m/s at the thesis's 2 s rotation)
  double height = 30.0;     // the mast, above the ground
  std::uint32_t grid = 100;
  std::vector<double> radii = {50, 100, 200, 400};  // region echoes' radii, metres
  int oracle_every = 10;    // the oracle checks every k-th rotation (0: none)
  int oracle_subdivisions = 1;
};

// report.json's "radar_echo"."moving_platform".
nlohmann::json radar_moving_platform(const Terrain& terrain, const PlatformOptions& options);
std::string radar_moving_platform_text(const nlohmann::json& platform);

}  // namespace cullcheck
