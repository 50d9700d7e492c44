// Buildings standing on a terrain (radar echo over a city on hills, thesis ch. 3.3): each of a
// city's buildings (core/scene.hpp, convex vertical prisms) placed on the ground under it.
//
// How a building's base follows the ground: its walls go down to the LOWEST ground under its
// footprint (so no line of sight passes under a wall on a slope: the wall is buried on the
// uphill side), and each prism's roof stands its height above the HIGHEST ground under the
// footprint (so the terrain never pokes through a roof and the building is at least its height
// tall everywhere). Both extremes are exact for the piecewise-linear terrain: they are found at
// the footprint's corners, where its edges cross the terrain's grid lines and diagonals, and at
// the terrain's vertices inside it.
//
// Triangle numbering, after the terrain's (core/terrain.hpp) and documented so the oracle can
// build the same triangles on its own: buildings in scene order, each building's prisms in
// order, each prism's walls first (ring edge k from corner k to k + 1: the lower triangle
// (k base, k+1 base, k+1 roof), then the upper (k base, k+1 roof, k roof); counter-clockwise
// seen from outside), then its roof as a fan from ring corner 0 ((0, k, k+1) at roof height,
// facing up). No floor: it is buried.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/scene.hpp"
#include "core/terrain.hpp"

namespace cullcheck {

struct StandingPrism {
  std::vector<Vec2> ring;  // convex, counter-clockwise
  double base = 0.0;       // the building's lowest ground
  double roof = 0.0;       // its highest ground + the prism's height
};

struct StandingBuilding {
  ObjectId id = 0;
  std::vector<StandingPrism> prisms;
};

struct TerrainScene {
  Terrain terrain;
  std::vector<StandingBuilding> buildings;
  std::string city;  // where the buildings came from (a replay's flags), empty: none
};

// The lowest and highest ground under a simple polygon (counter-clockwise); NaN when some of it
// lies off the terrain or over a NoData hole.
struct GroundRange {
  double lowest = 0.0, highest = 0.0;
};
GroundRange ground_under(const Terrain& terrain, const std::vector<Vec2>& polygon);

// The city's buildings stood on the terrain as above. Throws InputError naming the building
// when it stands partly off the terrain or over a hole, and when the scene holds mesh objects
// (only prism buildings can stand on terrain).
TerrainScene stand_on_terrain(Terrain terrain, const Scene& city, std::string city_source = {});

// Triangles of one prism and of one building in the numbering above.
inline std::size_t prism_triangle_count(const StandingPrism& p) { return 3 * p.ring.size() - 2; }
std::size_t building_triangle_count(const StandingBuilding& b);

// What a mast at plan point p stands on: the ground, or the roof of the highest prism there when
// p lies on a building (NaN off the terrain or over a hole).
double standing_height(const TerrainScene& scene, Vec2 p);

// The roof triangle seen from straight above at plan point p (the highest roof there), as its
// number among the buildings' triangles (add the terrain's triangle count for the global one),
// or -1 when p is on no building; `roof` receives its height.
std::int64_t roof_triangle_at(const TerrainScene& scene, Vec2 p, double* roof = nullptr);

// The index (into TerrainScene::buildings) of the first building one of whose prisms contains
// plan point p (boundary included), or -1.
std::int64_t building_at(const TerrainScene& scene, Vec2 p);

}  // namespace cullcheck
