// Seeded procedural cities (design: "generators/"). Every generator is a pure function of its
// parameters and a 64-bit seed: the same pair gives a byte-identical scene on any machine
// (hand-written distributions in random.hpp, coordinates on a 1 mm grid in grid_snap.hpp).
// Every building and mesh object goes through validate_and_finish(), the same rules a loaded
// scene obeys, and ids are 0..n-1 in generation order (unique across buildings and meshes). Each scene's provenance names the generator, the seed
// and the complete parameter set, so `--generator NAME --seed N --params JSON` rebuilds it.
//
// Generators (names accepted by make_city):
//   manhattan  blocks of lots on a street grid, with towers and thin slabs (the ΔH stress case:
//              thesis Fig. 3.10 - lateral movement past a building thinner than the step)
//   plaza      a Manhattan grid with an open square in the middle, optionally with kiosks lower
//              than the eye (occluders below eye height: the β_min check of ch. 3.1.2)
//   default    the CLI's city: a 12 x 12 Manhattan grid with a plaza, ~2,800 buildings
//   scatter    rotated rectangles scattered without overlaps
//   irregular  rotated, non-convex footprints (L, U, T) and convex polygons, no overlaps
//   thesis     the thesis testbed (ch. 3.2): 400 x 400 buildings of 46 triangles each
//   openings   what 2.5D prisms cannot express and real cullers get wrong (mesh objects): facade
//              walls with doors and windows through them and a low object behind that only the
//              openings show; arcades (upper floors on columns, open at street level: an
//              overhang) with a low object beneath; bridges over streets, open beneath; among
//              ordinary buildings (openings_city.cpp)
#pragma once

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace cullcheck::generators {

// Blocks are square, separated (and surrounded) by streets of one width; the city is centred
// on the origin. Each block is split into `buildings_per_block` lots (rows of equal lots, see
// manhattan_layout.hpp) and every lot holds one building. Lengths in metres.
struct ManhattanParams {
  int blocks_x = 8;
  int blocks_y = 8;
  double block_size = 80.0;
  double street_width = 16.0;        // wall line to wall line
  int buildings_per_block = 6;
  double setback = 1.0;              // least gap between a building and its lot boundary
  double width_jitter = 0.3;         // a building spans (1 - u * width_jitter) of its lot, u in [0, 1)
  double min_height = 8.0;
  double max_height = 40.0;
  double tower_fraction = 0.05;      // share of buildings drawn from the tower heights instead
  double tower_min_height = 60.0;
  double tower_max_height = 150.0;
  double thin_fraction = 0.1;        // share of buildings that are thin slabs across their lot
  double thin_min_width = 0.5;
  double thin_max_width = 2.0;
  int plaza_blocks_x = 0;            // blocks left empty in the middle (0 = no plaza)
  int plaza_blocks_y = 0;
  int kiosk_count = 0;               // low objects standing in the plaza's emptied blocks
  double kiosk_min_height = 1.0;
  double kiosk_max_height = 1.5;
  double kiosk_min_size = 1.5;
  double kiosk_max_size = 4.0;

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("blocks_x", s.blocks_x), v("blocks_y", s.blocks_y), v("block_size", s.block_size);
    v("street_width", s.street_width), v("buildings_per_block", s.buildings_per_block);
    v("setback", s.setback), v("width_jitter", s.width_jitter);
    v("min_height", s.min_height), v("max_height", s.max_height);
    v("tower_fraction", s.tower_fraction), v("tower_min_height", s.tower_min_height);
    v("tower_max_height", s.tower_max_height);
    v("thin_fraction", s.thin_fraction), v("thin_min_width", s.thin_min_width);
    v("thin_max_width", s.thin_max_width);
    v("plaza_blocks_x", s.plaza_blocks_x), v("plaza_blocks_y", s.plaza_blocks_y);
    v("kiosk_count", s.kiosk_count), v("kiosk_min_height", s.kiosk_min_height);
    v("kiosk_max_height", s.kiosk_max_height), v("kiosk_min_size", s.kiosk_min_size);
    v("kiosk_max_size", s.kiosk_max_size);
  }
};

// Rectangles of random size and orientation in a square area centred on the origin, placed by
// rejection against a grid of occupied boxes (bounded attempts: a crowded area holds fewer
// than `count` buildings, never an overlap).
struct ScatterParams {
  int count = 400;
  double area_size = 800.0;
  double min_size = 6.0;
  double max_size = 40.0;
  double min_height = 5.0;
  double max_height = 50.0;
  double rotated_fraction = 0.7;     // the rest are axis-aligned
  double thin_fraction = 0.1;
  double thin_min_width = 0.5;
  double thin_max_width = 2.0;
  double min_gap = 2.0;              // least distance between two buildings' bounding boxes
  int max_attempts = 50;             // candidates tried per building before giving up on it

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("count", s.count), v("area_size", s.area_size), v("min_size", s.min_size), v("max_size", s.max_size);
    v("min_height", s.min_height), v("max_height", s.max_height), v("rotated_fraction", s.rotated_fraction);
    v("thin_fraction", s.thin_fraction), v("thin_min_width", s.thin_min_width);
    v("thin_max_width", s.thin_max_width), v("min_gap", s.min_gap), v("max_attempts", s.max_attempts);
  }
};

// Rotated and non-convex footprints: rectangles, L-, U- and T-shapes and convex polygons
// (chosen by weight), placed like ScatterParams.
struct IrregularParams {
  int count = 300;
  double area_size = 900.0;
  double min_size = 12.0;
  double max_size = 50.0;
  double min_height = 5.0;
  double max_height = 50.0;
  double rotated_fraction = 0.8;
  double min_arm_width = 3.0;        // narrowest wing of an L, U or T
  double rectangle_weight = 1.0;
  double l_shape_weight = 1.0;
  double u_shape_weight = 1.0;
  double t_shape_weight = 1.0;
  double convex_weight = 1.0;
  int convex_min_vertices = 5;
  int convex_max_vertices = 12;
  double min_gap = 2.0;
  int max_attempts = 50;

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("count", s.count), v("area_size", s.area_size), v("min_size", s.min_size), v("max_size", s.max_size);
    v("min_height", s.min_height), v("max_height", s.max_height), v("rotated_fraction", s.rotated_fraction);
    v("min_arm_width", s.min_arm_width), v("rectangle_weight", s.rectangle_weight);
    v("l_shape_weight", s.l_shape_weight), v("u_shape_weight", s.u_shape_weight);
    v("t_shape_weight", s.t_shape_weight), v("convex_weight", s.convex_weight);
    v("convex_min_vertices", s.convex_min_vertices), v("convex_max_vertices", s.convex_max_vertices);
    v("min_gap", s.min_gap), v("max_attempts", s.max_attempts);
  }
};

// The thesis testbed (ch. 3.2): grid_x * grid_y buildings of 46 triangles each (16-vertex convex
// footprints: squares with rounded corners), in blocks of buildings_per_block_side^2 buildings
// separated by streets. The thesis gives only the counts; sizes here are our choice.
struct ThesisParams {
  int grid_x = 400;
  int grid_y = 400;
  double building_size = 20.0;
  double building_gap = 4.0;         // between neighbours inside a block
  int buildings_per_block_side = 5;
  double street_width = 16.0;        // between blocks
  double corner_radius = 3.0;
  double min_height = 10.0;
  double max_height = 60.0;

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("grid_x", s.grid_x), v("grid_y", s.grid_y), v("building_size", s.building_size);
    v("building_gap", s.building_gap), v("buildings_per_block_side", s.buildings_per_block_side);
    v("street_width", s.street_width), v("corner_radius", s.corner_radius);
    v("min_height", s.min_height), v("max_height", s.max_height);
  }
};

// A street grid (manhattan_layout.hpp's, centred on the origin) whose square blocks hold an inner
// core of lots with ordinary buildings, four corner buildings, and along each of the four street
// fronts a strip `frontage_depth` deep holding, drawn by weight, one of:
//   facade  a wall slab at the street edge (a MeshObject, thickness and height drawn) cut into
//           bays and storeys, with doors (ground floor) and windows through it, at least one on
//           the ground floor; behind it a low building (target_*) lower than the wall, which a
//           street-level eye sees only through the openings;
//   arcade  a slab (upper floors, arcade_min/max_slab thick) held at a drawn clearance above the
//           street by a row of columns along the street edge (one MeshObject), with a low
//           building under the overhang;
//   plain   one to three ordinary buildings.
// bridge_count bridges (MeshObject decks, drawn among the streets between two blocks) span a
// street from one block's core to the other's at a drawn height, over both blocks' strips, which
// are then left empty. Every object is `setback` clear of every other. Lengths in metres.
struct OpeningsParams {
  int blocks_x = 3;
  int blocks_y = 3;
  double block_size = 48.0;
  double street_width = 14.0;
  double frontage_depth = 8.0;
  int core_buildings = 4;            // lots of the inner core, one building each
  double setback = 0.5;              // least gap between two objects (and to a lot's edge)
  double min_height = 8.0;           // core, corner and plain buildings
  double max_height = 30.0;
  double facade_weight = 0.4;        // chances of each frontage kind
  double arcade_weight = 0.3;
  double plain_weight = 0.3;
  double wall_min_thickness = 0.2;
  double wall_max_thickness = 0.6;
  double wall_min_height = 6.0;
  double wall_max_height = 12.0;
  double storey_height = 3.0;
  double bay_width = 3.0;            // a wall is cut into bays about this wide, one opening at most each
  double door_fraction = 0.3;        // ground-floor bays with a door (else maybe a window)
  double door_min_width = 0.9;
  double door_max_width = 2.0;
  double door_min_height = 2.0;
  double door_max_height = 2.6;
  double window_fraction = 0.6;      // bays of each storey with a window
  double window_min_width = 0.8;
  double window_max_width = 2.0;
  double window_min_height = 0.8;
  double window_max_height = 1.6;
  double sill_height = 0.9;          // window bottom above its storey's floor
  double target_min_height = 1.0;    // the low building behind a facade or under an arcade
  double target_max_height = 2.5;
  double arcade_min_clearance = 3.0; // open height under the arcade's slab
  double arcade_max_clearance = 5.0;
  double arcade_min_slab = 3.0;
  double arcade_max_slab = 9.0;
  double column_size = 0.5;
  double column_spacing = 4.0;
  int bridge_count = 2;
  double bridge_min_height = 5.0;    // underside of the deck
  double bridge_max_height = 15.0;
  double bridge_thickness = 1.0;
  double bridge_min_width = 3.0;
  double bridge_max_width = 6.0;

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("blocks_x", s.blocks_x), v("blocks_y", s.blocks_y), v("block_size", s.block_size);
    v("street_width", s.street_width), v("frontage_depth", s.frontage_depth), v("core_buildings", s.core_buildings);
    v("setback", s.setback), v("min_height", s.min_height), v("max_height", s.max_height);
    v("facade_weight", s.facade_weight), v("arcade_weight", s.arcade_weight), v("plain_weight", s.plain_weight);
    v("wall_min_thickness", s.wall_min_thickness), v("wall_max_thickness", s.wall_max_thickness);
    v("wall_min_height", s.wall_min_height), v("wall_max_height", s.wall_max_height);
    v("storey_height", s.storey_height), v("bay_width", s.bay_width);
    v("door_fraction", s.door_fraction), v("door_min_width", s.door_min_width), v("door_max_width", s.door_max_width);
    v("door_min_height", s.door_min_height), v("door_max_height", s.door_max_height);
    v("window_fraction", s.window_fraction), v("window_min_width", s.window_min_width);
    v("window_max_width", s.window_max_width), v("window_min_height", s.window_min_height);
    v("window_max_height", s.window_max_height), v("sill_height", s.sill_height);
    v("target_min_height", s.target_min_height), v("target_max_height", s.target_max_height);
    v("arcade_min_clearance", s.arcade_min_clearance), v("arcade_max_clearance", s.arcade_max_clearance);
    v("arcade_min_slab", s.arcade_min_slab), v("arcade_max_slab", s.arcade_max_slab);
    v("column_size", s.column_size), v("column_spacing", s.column_spacing);
    v("bridge_count", s.bridge_count), v("bridge_min_height", s.bridge_min_height);
    v("bridge_max_height", s.bridge_max_height), v("bridge_thickness", s.bridge_thickness);
    v("bridge_min_width", s.bridge_min_width), v("bridge_max_width", s.bridge_max_width);
  }
};

// Defaults of the named Manhattan variants.
ManhattanParams plaza_params();         // 8 x 8 blocks, 2 x 2 plaza, 6 kiosks
ManhattanParams default_city_params();  // 12 x 12 blocks of 20 lots, 2 x 2 plaza: ~2,800 buildings

// Throw InputError(object "generator", field = parameter name) for unusable values; the
// problem text names `generator`.
void validate(const ManhattanParams& p, const std::string& generator = "manhattan");
void validate(const ScatterParams& p, const std::string& generator = "scatter");
void validate(const IrregularParams& p, const std::string& generator = "irregular");
void validate(const ThesisParams& p, const std::string& generator = "thesis");
void validate(const OpeningsParams& p, const std::string& generator = "openings");

Scene manhattan_city(const ManhattanParams& p, std::uint64_t seed);
Scene plaza_city(const ManhattanParams& p, std::uint64_t seed);  // requires a plaza
Scene default_city(std::uint64_t seed);
Scene scatter_city(const ScatterParams& p, std::uint64_t seed);
Scene irregular_city(const IrregularParams& p, std::uint64_t seed);
Scene thesis_city(const ThesisParams& p, std::uint64_t seed);
Scene openings_city(const OpeningsParams& p, std::uint64_t seed);

// Dispatch by name. `params` is a JSON object overlaid on that generator's defaults (null or {}
// for the defaults); unknown generator names, unknown parameter names, wrong types and bad
// values raise InputError with object "generator".
const std::vector<std::string>& city_generator_names();
Scene make_city(const std::string& generator_name, std::uint64_t seed, const nlohmann::json& params);

// The complete parameter set of a generator after overlaying `params` on its defaults, as
// stored in Provenance::parameters_json.
nlohmann::json resolved_city_params(const std::string& generator_name, const nlohmann::json& params);

// The street grid of a scene made by manhattan, plaza, default, thesis or openings (read back from its
// provenance), so camera paths can follow its streets; nullopt for other scenes.
std::optional<ManhattanParams> manhattan_params_of(const Scene& scene);
// The Manhattan street grid that a thesis city's streets coincide with (its blocks of
// buildings_per_block_side^2 buildings as blocks); nullopt when the grid is not whole blocks.
std::optional<ManhattanParams> thesis_street_grid(const ThesisParams& t);

}  // namespace cullcheck::generators
