// Detailed building meshes on a city layout (the slice-wise paper's scenes in kind: buildings
// with real vertical complexity, 100 to 10,000 triangles each).
//
// Each building of a Manhattan-family layout (its axis-aligned footprint and height) becomes one
// mesh object made of closed solids: walls with recessed windows in a grid of storeys and bays
// (facade relief), a podium with a tower set back on it, pitched (gable) and hipped roofs, and
// arcades (the ground storey set back behind a row of columns under the floor above). Every
// solid is closed and outward-facing, so the mesh is closed (MeshObject::closed) and Minkowski
// shrinking applies to it. The mesh stays inside the building's footprint and height.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene.hpp"
#include "generators/city.hpp"

namespace cullcheck::generators {

struct DetailedCityParams {
  ManhattanParams layout;          // the city the buildings stand in (its lots, heights and streets)
  double storey_height = 3.3;      // metres, adjusted so a building holds whole storeys
  double bay_width = 3.6;          // window pitch along a wall, metres (widened to keep max_triangles)
  double window_share = 0.6;       // share of a bay's width (and of a storey's height, less the sill) glazed
  double window_depth = 0.3;       // recess, metres (at most a quarter of the building's thinner side)
  double tower_fraction = 0.4;     // buildings over 25 m: a podium with a tower set back on it
  double pitched_fraction = 0.25;  // buildings up to 25 m: a gable roof
  double hipped_fraction = 0.2;    //                       a hipped roof
  double arcade_fraction = 0.2;    // an arcade along the south side (deep enough footprints)
  double plain_fraction = 0.1;     // blank walls, storey lines only (sheds, warehouses, party walls)
  int max_triangles = 10000;       // per building

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    ManhattanParams::visit(s.layout, v);
    v("storey_height", s.storey_height), v("bay_width", s.bay_width), v("window_share", s.window_share);
    v("window_depth", s.window_depth), v("tower_fraction", s.tower_fraction), v("pitched_fraction", s.pitched_fraction);
    v("hipped_fraction", s.hipped_fraction), v("arcade_fraction", s.arcade_fraction), v("plain_fraction", s.plain_fraction);
    v("max_triangles", s.max_triangles);
  }
};

void validate(const DetailedCityParams& p, const std::string& generator = "detailed");
// The layout's buildings as detailed meshes (ids kept); the scene holds meshes only.
Scene detailed_city(const DetailedCityParams& p, std::uint64_t seed);
// One building's mesh inside the box [lo, hi] (plan) from the ground to `height`.
MeshObject detailed_building(ObjectId id, Vec2 lo, Vec2 hi, double height, const DetailedCityParams& p, std::uint64_t seed);

}  // namespace cullcheck::generators
