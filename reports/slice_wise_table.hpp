// Slice-wise PVS (Yılmaz & Güdükbay 2007) measured as the paper's Tables 1-3 and Fig. 7, in one
// run, on a detailed generated city and (given a file) a real LoD2 CityJSON district:
//  - Table 1, the model: triangles, objects, extent, view-cell size, navigable cells;
//  - Table 2, the preprocessing: slices, triangle pointers and their memory, PVS time per cell,
//    shrinking time per object, totals;
//  - Table 3, the walk: triangles rendered per frame, slice-wise against building-level culling,
//    the same cells (the walk's), the same frames (each frame's cell PVS inside its frustum);
//  - Fig. 7, storage of one cell's PVS: 3 bytes per object against a per-triangle bitmap, a
//    building-level list and a regular octree per visible object;
//  - Fig. 2's premise: the share of partially visible objects whose hidden slices form one
//    rectangle from a side (the one Algorithm 3 keeps), and the triangles it gives up;
//  - the oracle's check: from the corners, edge midpoints and centre of some cells, every
//    witnessed triangle must lie in a kept slice; violations fail the gate.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/slice_wise/cell_culling.hpp"
#include "engine/slice_wise/slice_scene.hpp"
#include "engine/slice_wise/slicing.hpp"
#include "generators/detailed_buildings.hpp"
#include "reports/claims.hpp"

namespace cullcheck {

struct SliceTableOptions {
  std::uint64_t seed = 1;
  int frames = 300;                   // street-walk frames per city; their cells are the view cells
  double cell_side = 2.0;             // metres; ε = side / √2
  // Queries: hidden heights in steps of 0.5 m (the engine's default Δ is 1 m; a slice's hidden
  // height then lands nearer the tops of the triangles in it).
  slice_wise::CellCullingOptions culling = [] {
    slice_wise::CellCullingOptions c;
    c.delta = 0.5;
    return c;
  }();
  // Slices of 1.5 m, up to 64 per axis. The paper's are as wide as its cells "although they can be
  // different to adapt to the dimensions of the buildings", with about 25 on the height axis and
  // no cap below what a byte holds: measured on the generated city (both axes, Δ 0.5), 2 m slices
  // render 45.4% of building-level, 1.5 m 44.7%, for 13% more slice memory.
  slice_wise::SlicingOptions slicing = [] {
    slice_wise::SlicingOptions s;
    s.slice_m = 1.5;
    s.max_slices = 64;
    return s;
  }();
  int oracle_cells = 4;               // cells checked by the oracle, spread over the walk
  int oracle_eyes_per_side = 3;       // eyes per checked cell: an n x n grid, corners included (n >= 2)
  std::string cityjson;               // a LoD2 CityJSON file for the real-city row; empty: none
  bool generated = true;              // the generated detailed city's row (false: the CityJSON file's only)
  // The runs: as published (Minkowski vertex shrinking, other objects only, one vertical axis),
  // then cullcheck's variants: the corrected occluders (voxel erosion) with a hidden rectangle on
  // both vertical axes, then with each object's own shrunk solid as an occluder too.
  struct Run {
    slice_wise::Shrinking shrinking = slice_wise::Shrinking::minkowski_mesh;
    bool self_occlusion = false;
    bool both_vertical_axes = false;  // CellCullingOptions::both_vertical_axes
  };
  std::vector<Run> runs{{slice_wise::Shrinking::minkowski_mesh, false, false},
                        {slice_wise::Shrinking::voxel_erosion, false, true},
                        {slice_wise::Shrinking::voxel_erosion, true, true}};
  double voxel_m = 0.25;              // voxel_erosion's grid (SliceSceneOptions::voxel_m)
  // The generated city: the default city's layout (2,808 buildings) in detailed meshes; the walk
  // follows its streets.
  generators::DetailedCityParams detailed = [] {
    generators::DetailedCityParams p;
    p.layout = generators::default_city_params();
    return p;
  }();
  unsigned threads = 0;               // cells at once (0: every core); figures do not depend on it
};

nlohmann::json slice_wise_table(const SliceTableOptions& options);
// The ledger's entries from the table: conservative at slice granularity as published
// (yilmaz-slice-conservative) and with the corrected occluders (cullcheck-slice-voxel-erosion),
// and the paper's rendered share (yilmaz-slice-half-of-building-level: at most 55% of the
// building-level triangles per frame, for the paper's 49%).
std::vector<ClaimCheck> slice_wise_claims(const nlohmann::json& table);
std::string slice_wise_table_text(const nlohmann::json& table);
// Witnessed triangles outside the kept slices, over every city of the table.
std::uint64_t slice_table_violations(const nlohmann::json& table);

}  // namespace cullcheck
