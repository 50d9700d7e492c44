// Radar echo images (thesis Fig. 3.16): the visible triangles seen from above, north up, east
// to the right, over the square of side 2 x range centred on the transmitter. A visible
// triangle's return is brighter the more squarely it faces the transmitter (the cosine between
// its normal and the direction to the transmitter, at its centroid); everything else is dark.
// Range rings every fifth of the range, the transmitter marked in the centre.
//
// The difference image compares a method's PVS with the oracle's witnessed set: green where
// both have the triangle, amber where only the PVS does (over-estimate), red where only the
// oracle does (missed: a conservative method must have none).
//
// Each pixel shows the triangle under its centre (found from the grid, O(1) a pixel), so the
// pictures cost image size, not triangle count; the same inputs give the same bytes.
#pragma once

#include <cstdint>
#include <vector>

#include "core/terrain.hpp"
#include "core/terrain_scene.hpp"
#include "reports/pictures.hpp"

namespace cullcheck {

namespace echo_colours {
inline constexpr Rgb kNoReturn{8, 16, 12};
inline constexpr Rgb kOffTerrain{40, 40, 48};
inline constexpr Rgb kRing{70, 110, 90};
inline constexpr Rgb kTransmitter{255, 255, 255};
inline constexpr Rgb kBoth{60, 170, 75};
inline constexpr Rgb kOverEstimate{245, 180, 40};
inline constexpr Rgb kMissed{255, 0, 0};
inline constexpr Rgb kNeither{30, 30, 30};
}  // namespace echo_colours

// `visible`: triangle numbers, ascending. With buildings standing on the terrain, a pixel on a
// building shows its roof (a roof's return faces straight up).
RgbImage echo_image(const Terrain& terrain, const std::vector<std::uint32_t>& visible, Vec3 transmitter, double range, int size);
RgbImage echo_image(const TerrainScene& scene, const std::vector<std::uint32_t>& visible, Vec3 transmitter, double range, int size);
RgbImage echo_difference_image(const Terrain& terrain, const std::vector<std::uint32_t>& pvs,
                               const std::vector<std::uint32_t>& witnessed, Vec3 transmitter, double range, int size);
RgbImage echo_difference_image(const TerrainScene& scene, const std::vector<std::uint32_t>& pvs,
                               const std::vector<std::uint32_t>& witnessed, Vec3 transmitter, double range, int size);

// The triangle under plan point p, or -1 outside the grid or over a hole.
std::int64_t triangle_at(const Terrain& terrain, Vec2 p);

}  // namespace cullcheck
