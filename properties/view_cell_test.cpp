// View-cell PVSs (thesis ch. 5.1 over ch. 4's shrinking): the circle tiling of Fig. 4.9d, the
// boundary samples, the street cells they run on, carrying decisions between samples, and the
// oracle's check that a cell's PVS holds from eyes anywhere in the cell (corners, edges,
// interior) for every region method that claims to be conservative, with both samplings.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <set>

#include "engine/method.hpp"
#include "engine/shrinking/circle_tiling.hpp"
#include "engine/shrinking/view_cell.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "generators/navigable_regions.hpp"
#include "generators/street_cells.hpp"
#include "oracle/oracle.hpp"
#include "properties/method_options_gen.hpp"
#include "properties/property_oracle.hpp"
#include "properties/property_run.hpp"
#include "reports/view_cells.hpp"

namespace cullcheck {
namespace {

namespace rcgen = generators::rcgen;

// Points of a fine grid, including far from the origin: each lies within ε of its nearest centre
// (the hexagonal Voronoi cell's circumradius), and no other centre is nearer.
TEST(CircleTiling, EveryPointIsWithinEpsilonOfItsNearestCentre) {
  for (double epsilon : {0.1, 1.4142135623730951, 5.0})
    for (double base : {0.0, -3.7e5, 6.1e6}) {
      const CircleTiling tiling{epsilon};
      for (int i = 0; i < 60; ++i)
        for (int j = 0; j < 60; ++j) {
          const Vec2 p{base + i * epsilon * 0.137, base + j * epsilon * 0.113};
          const Vec2 c = tiling.nearest_centre(p);
          EXPECT_LE(length(c - p), epsilon * (1 + 1e-9)) << "point " << p.x << "," << p.y << " eps " << epsilon;
        }
    }
  // Spacing √3 ε: the six neighbours of a centre are √3 ε away (Fig. 4.9d's overlap), not ε
  // (4.9a-b) nor 2ε (4.9c, holes).
  const CircleTiling t{1.0};
  EXPECT_NEAR(length(t.centre(1, 0) - t.centre(0, 0)), std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(length(t.centre(0, 1) - t.centre(0, 0)), std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(length(t.centre(-1, 1) - t.centre(0, 0)), std::sqrt(3.0), 1e-12);
}

TEST(CircleTiling, CentresCoveringACellCoverEveryPointOfIt) {
  const std::vector<Vec2> cell{{3, -2}, {43, -2}, {43, 14}, {3, 14}};
  for (double epsilon : {0.5, 1.4142135623730951, 6.0}) {
    const std::vector<Vec2> centres = CircleTiling{epsilon}.centres_covering(cell);
    std::set<std::pair<double, double>> unique;
    for (Vec2 c : centres) unique.insert({c.x, c.y});
    EXPECT_EQ(unique.size(), centres.size());
    for (int i = 0; i <= 80; ++i)
      for (int j = 0; j <= 32; ++j) {
        const Vec2 p{3 + 40.0 * i / 80, -2 + 16.0 * j / 32};
        double nearest = HUGE_VAL;
        for (Vec2 c : centres) nearest = std::min(nearest, length(c - p));
        EXPECT_LE(nearest, epsilon * (1 + 1e-9));
      }
    // Serpentine order: consecutive centres are neighbours or the turn between two rows.
    for (std::size_t k = 1; k < centres.size(); ++k) EXPECT_LE(length(centres[k] - centres[k - 1]), 2 * epsilon + 40.0);
  }
}

TEST(BoundarySamples, AtMostTwoEpsilonApartAndEveryCorner) {
  const std::vector<Vec2> cell{{0, 0}, {10, 0}, {10, 3}, {0, 3}};
  const std::vector<Vec2> s = boundary_samples(cell, 1.0);
  ASSERT_EQ(s.size(), 5u + 2u + 5u + 2u);
  for (Vec2 corner : cell) EXPECT_NE(std::find(s.begin(), s.end(), corner), s.end());
  for (std::size_t k = 0; k < s.size(); ++k) EXPECT_LE(length(s[(k + 1) % s.size()] - s[k]), 2.0 + 1e-12);
}

TEST(ViewCell, BadCellsAreRejectedWithTheReason) {
  auto message = [](const ViewCell& cell, double epsilon, CellSampling sampling) {
    try {
      cell_samples(cell, epsilon, sampling);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::vector<Vec2> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  EXPECT_NE(message({{{0, 0}, {10, 0}}, 1.7}, 1.0, CellSampling::boundary).find("at least 3"), std::string::npos);
  EXPECT_NE(message({{{0, 0}, {0, 10}, {10, 10}, {10, 0}}, 1.7}, 1.0, CellSampling::boundary).find("counter-clockwise"),
            std::string::npos);
  EXPECT_NE(message({{{0, 0}, {10, 0}, {5, 2}, {10, 10}, {0, 10}}, 1.7}, 1.0, CellSampling::tiled).find("convex"),
            std::string::npos);
  EXPECT_NE(message({square, 1.7}, 0.0, CellSampling::boundary).find("positive"), std::string::npos);
  EXPECT_NE(message({square, 1.7}, NAN, CellSampling::boundary).find("positive"), std::string::npos);
  EXPECT_NE(message({square, 1.7}, 1e-6, CellSampling::tiled).find("limit"), std::string::npos);
  EXPECT_EQ(message({square, 1.7}, 1.0, CellSampling::tiled), "accepted");
}

// Street cells of a Manhattan city: crossings, stretches and plaza blocks; neighbours share an
// edge both ways; no building stands in a street cell.
TEST(StreetCells, GraphIsSymmetricAndCellsHoldNoBuilding) {
  const Scene scene = generators::make_city("plaza", 3, {{"blocks_x", 5}, {"blocks_y", 4}, {"plaza_blocks_x", 2}, {"plaza_blocks_y", 2}});
  const auto cells = generators::street_cells_of(scene);
  ASSERT_TRUE(cells.has_value());
  const std::size_t crossings = 6 * 5, stretches = 6 * 4 + 5 * 5, plaza = 4;
  ASSERT_EQ(cells->size(), crossings + stretches + plaza);
  for (const auto& c : *cells) {
    EXPECT_EQ(c.id, &c - cells->data());
    EXPECT_TRUE(is_convex(c.ring));
    EXPECT_GT(signed_area(c.ring), 0.0);
    for (std::uint32_t n : c.neighbours) {
      EXPECT_NE(n, c.id);
      const auto& back = (*cells)[n].neighbours;
      EXPECT_TRUE(std::binary_search(back.begin(), back.end(), c.id)) << c.id << " -> " << n;
    }
    if (c.kind == "crossing") {
      EXPECT_TRUE(c.neighbours.size() >= 2 && c.neighbours.size() <= 4);
    }
    if (c.kind == "plaza") {
      EXPECT_EQ(c.neighbours.size(), 4u);
    }
    if (c.kind == "plaza") continue;  // kiosks may stand in the plaza's blocks
    Box2 box;
    for (Vec2 v : c.ring) box.extend(v);
    for (const Building& b : scene.buildings) {
      const Box2 bb = b.bounds.plan();
      const bool overlap = bb.lo.x < box.hi.x && bb.hi.x > box.lo.x && bb.lo.y < box.hi.y && bb.hi.y > box.lo.y;
      EXPECT_FALSE(overlap) << "building " << b.id << " in street cell " << c.id;
    }
  }
  // Stretches touch two crossings; an inner crossing touches four stretches.
  for (const auto& c : *cells)
    if (c.kind == "street") {
      EXPECT_GE(c.neighbours.size(), 2u);
    }
  EXPECT_EQ((*cells)[1 * 6 + 1].neighbours.size(), 4u);
}

// Carrying decisions from sample to sample leaves every cell's union as it was.
TEST(ViewCell, CarryingDecisionsKeepsTheUnion) {
  const Scene scene = generators::make_city("default", 1, nlohmann::json::object());
  const auto cells = generators::street_cells_of(scene);
  ASSERT_TRUE(cells.has_value());
  for (const std::string& name : region_method_names()) {
    auto method = make_region_method(name, scene);
    ViewCellPvs cells_pvs(*method, scene);
    for (CellSampling sampling : {CellSampling::boundary, CellSampling::tiled})
      for (std::size_t c = 7; c < cells->size(); c += 97) {
        const ViewCell cell{(*cells)[c].ring, 1.7};
        const ViewCellResult plain = cells_pvs.compute(cell, 1.4142135623730951, sampling, false);
        const ViewCellResult carried = cells_pvs.compute(cell, 1.4142135623730951, sampling, true);
        EXPECT_EQ(plain.pvs, carried.pvs) << name << " " << cell_sampling_name(sampling) << " cell " << c;
        if (method->carries_known()) {
          EXPECT_LT(carried.stats.buildings_tested, plain.stats.buildings_tested);
        }
      }
  }
}

struct CellCase {
  generators::SceneSpec spec;
  std::size_t cell_pick = 0;
  double epsilon = 1.0;
  std::string method;
  CellSampling sampling = CellSampling::boundary;
};
void showValue(const CellCase& c, std::ostream& os) {
  os << c.spec << " cell pick " << c.cell_pick << " eps " << c.epsilon << " " << c.method << " "
     << cell_sampling_name(c.sampling);
}

std::vector<std::string> conservative_region_methods() {
  std::vector<std::string> out;
  const Scene empty;
  for (const std::string& n : region_method_names())
    if (make_region_method(n, empty)->claims_conservative()) out.push_back(n);
  return out;
}

rc::Gen<CellCase> cell_case(rc::Gen<generators::SceneSpec> specs = rc::gen::oneOf(rcgen::manhattan_spec(), rcgen::irregular_spec())) {
  return rc::gen::map(rc::gen::tuple(std::move(specs),
                                     rc::gen::inRange<std::size_t>(0, 1000),
                                     rc::gen::element(0.5, 1.4142135623730951, 4.0),
                                     rc::gen::elementOf(conservative_region_methods()),
                                     rc::gen::element(CellSampling::boundary, CellSampling::tiled)),
                      [](const auto& t) {
                        return CellCase{std::get<0>(t), std::get<1>(t), std::get<2>(t), std::get<3>(t), std::get<4>(t)};
                      });
}

// The oracle, from corners, edge midpoints and interior eyes of a navigable region (a street cell,
// or a free-space cell of an irregular city: generators/navigable_regions.hpp), sees nothing
// outside the cell's PVS, whichever sampling (boundary: the published claim; tiled: by
// construction), conservative disc method and engine options (method_options_gen.hpp) are used.
void check_cell(const CellCase& c) {
  const Scene scene = generators::scene_of(c.spec);
  const std::vector<NavigableRegion> cells = generators::navigable_regions(scene);
  const std::size_t id = c.cell_pick % cells.size();
  const ViewCell cell{cells[id].ring, 1.7};
  const MethodOptions options = *method_options();
  auto method = make_region_method(c.method, scene, options);
  const std::vector<ObjectId> pvs = ViewCellPvs(*method, scene).compute(cell, c.epsilon, c.sampling, true).pvs;
  const oracle::Oracle truth(scene);
  SceneSource source;
  source.generator = c.spec.generator;
  source.seed = c.spec.seed;
  source.parameters_json = c.spec.params.dump();
  for (const Camera& v : cell_viewpoints(cell)) {
    const oracle::OracleAnswer seen = truth.visible_set(v, property_oracle());
    for (ObjectId b : seen.visible)
      if (!std::binary_search(pvs.begin(), pvs.end(), b))
        RC_FAIL(c.method + " (" + std::string(cell_sampling_name(c.sampling)) + ") misses building " + std::to_string(b) +
                " of cell " + std::to_string(id) + ": " +
                (seen.sampling ? oracle::describe(seen.sampling->witnesses.at(b)) : seen.model) + "; replay: " +
                cell_replay_command(source, c.method, static_cast<std::uint32_t>(id), c.epsilon, c.sampling, 1.7, v) + " " +
                option_flags(options) + " --spacing 3 --frustum-resolution 128");
  }
}

RC_GTEST_PROP(ViewCell, PvsHoldsFromEveryEyeInTheCell, ()) { check_cell(*cell_case()); }

// The same on the large occluded Manhattan grids (rapidcheck_gens.hpp), where most of the city is
// hidden from a cell: fewer cases, each costs a dozen oracle queries over hundreds of buildings.
TEST(ViewCell, PvsHoldsFromEveryEyeInTheCellOfOccludedGrids) {
  const PropertyOutcome run =
      run_property("view-cell PVS holds on occluded Manhattan grids", 30, true, [] { check_cell(*cell_case(rcgen::occluded_manhattan_spec())); });
  EXPECT_TRUE(run.held) << "a view cell's PVS misses a building the oracle sees (case and replay above)";
}

}  // namespace
}  // namespace cullcheck
