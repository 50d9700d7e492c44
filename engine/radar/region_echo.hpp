// A radar echo valid for a whole region of mast positions (thesis ch. 3.3: the moving
// platform): the triangles visible from some eye in a vertical cylinder, plan within `radius`
// of `centre` and height in [z_low, z_high], so that one echo serves every rotation while the
// platform stays inside.
//
// How: the conservative rule's sweep (radar_echo.hpp) from the cylinder's top centre
// C = (centre, z_high), every triangle tested as it is, every shadow cast by the solid eroded by
// `radius` in plan (occluder shrinking, as in thesis ch. 4 and Wonka et al. 2000): a triangle's
// shadow stands at its floor, the lowest ground under its plan grown by `radius`, or its far
// chain's lowest vertex less the most the ground can fall within `radius` of it, whichever is
// higher: the eroded solid lies above that all along the chain (buildings shrink to their
// ground; a terrain with holes casts no shadows, as ever).
//
// Why that serves every eye E of the cylinder that stands above the ground and outside the
// buildings: first raise E to E' = (E's plan, z_high). Over a height field (the terrain, and
// buildings solid down to the ground) what E sees E' sees too: the segment from E' to a point
// runs above the one from E. Now say the sweep hid q from C: C's segment to q passes through
// the eroded solid at some s. E''s segment to q holds the point s' at the same fraction of the
// way, s' = s + (1 - f)(E' - C): at s's height and at most `radius` away in plan, so inside the
// uneroded solid (the eroded solid at s means solid everywhere within `radius` of it in plan,
// at that height). So E' cannot see q, nor can E. Facing is decided over the whole cylinder,
// and a sector is the eyes' own (widened by asin(radius / d) at plan distance d).
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "engine/radar/radar_echo.hpp"
#include "engine/radar/triangle_grid.hpp"

namespace cullcheck::radar {

struct MastRegion {
  Vec2 centre;
  double radius = 0.0;
  double z_low = 0.0, z_high = 0.0;
};

// Per triangle of the grid's surface, two bounds of the surface's solid eroded by `radius` in
// plan (ShrunkOccluders): its floor, the lowest terrain vertex whose grid cell meets the
// triangle's plan box grown by `radius` (-inf with holes); and for a terrain triangle its drop,
// radius x the steepest gradient of the cells that box meets, so that the ground within
// `radius` of a point of the triangle lies at most that far below the point (+inf for a
// building's). O(vertices + triangles) per radius.
struct ShrunkFloors {
  std::vector<double> floors, drops;
};
ShrunkFloors eroded_floors(const RadarSurface& surface, double radius);

class RegionEcho {
 public:
  explicit RegionEcho(const TriangleGrid& grid, std::uint32_t horizon_bins = 16384);
  // The triangles visible from some eye of `region` within `sector` (azimuths from the eye).
  // The centre must lie over the grid; throws std::invalid_argument on a region that is not one.
  Echo compute(const MastRegion& region, const Sector& sector = {});

 private:
  const TriangleGrid& grid_;
  RadarEcho echo_;
  double floors_radius_ = -1.0;  // the radius floors_ were eroded for
  ShrunkFloors floors_;
};

}  // namespace cullcheck::radar
