// Polar diagrams (Ortega, Rueda and Feito, section 5) measured against CGAL's exact visibility
// polygon, in one run:
//  - construction: the four polar diagrams, the fan's grids, and CGAL's arrangement and
//    triangulation (oracle/exact_2d.hpp), on the default city and on a city like the paper's
//    (600 star-shaped non-convex footprints, 45,000 vertices; the paper builds each diagram in
//    100 ms on a 2.4 GHz Pentium IV);
//  - per frame along a level street walk (a 90-degree view, as the paper's walk, and all
//    round): the fan's query time against CGAL's visibility polygon, their visible sets compared
//    building for building (any difference is counted and fails the gate), rays thrown against
//    2k for k visible buildings (the paper's O(2k) claim), visible edges;
//  - how the fan's query time grows with the visible count k at fixed n (views of 10 to 360
//    degrees from the same eyes, binned by k).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace cullcheck {

struct PolarTableOptions {
  int frames = 200;        // walk frames per city and view
  int build_repeats = 3;   // construction timed this often (median)
  std::uint64_t seed = 1;
};

nlohmann::json polar_diagram_table(const PolarTableOptions& options);
std::string polar_diagram_table_text(const nlohmann::json& table);
// Frames where the fan and CGAL disagree (0 when the table holds none).
std::uint64_t polar_table_mismatches(const nlohmann::json& table);

}  // namespace cullcheck
