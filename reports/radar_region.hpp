// The radar's region echo (engine/radar/region_echo.hpp) run for a mast that may stand anywhere
// in a disc: the cylinder of its possible eyes (the mast's height above the ground or the roof
// under it, anywhere in the disc), and the check of one region echo against the terrain oracle
// from sample positions in the disc (its centre, its rim, half-way out).
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "core/terrain_scene.hpp"
#include "engine/radar/radar_echo.hpp"
#include "engine/radar/region_echo.hpp"
#include "engine/radar/triangle_grid.hpp"
#include "oracle/terrain_oracle.hpp"

namespace cullcheck {

// Every eye a mast `height` above what it stands on can have within `radius` of `centre`: the
// heights run from the lowest ground to the highest ground or roof under the disc's bounding
// square (clipped to the terrain), plus the height. Throws InputError when the centre is off
// the terrain or over a hole.
radar::MastRegion mast_region(const TerrainScene& scene, Vec2 centre, double radius, double height);

// Eyes of the region to check from: the centre, `rim` points on the rim and `rim` half-way out
// (turned by half a step), each `height` above what it stands on; positions off the terrain or
// over holes are left out.
std::vector<Vec3> region_sample_eyes(const TerrainScene& scene, Vec2 centre, double radius, double height, int rim);

struct RegionCheck {
  radar::Echo echo;                  // the region's
  std::size_t samples = 0;
  std::size_t missed = 0;            // witnessed triangles, summed over the samples, the region's PVS lacks
  std::size_t centre_echo_missed = 0;  // the same for the conservative point echo from the centre
  std::size_t witnessed_union = 0;   // triangles some sample witnessed
  std::vector<std::uint32_t> first_missed;  // per sample with a miss: the first triangle
};

// The region echo over `sector` held to the oracle from region_sample_eyes; `truth` built on
// `scene`; the witness options' sector is set from `sector`.
RegionCheck check_region_echo(const TerrainScene& scene, const radar::TriangleGrid& grid, const oracle::TerrainOracle& truth,
                              Vec2 centre, double radius, double height, int rim, const radar::Sector& sector,
                              oracle::TerrainWitnessOptions witness);

}  // namespace cullcheck
