// Generated terrains (generators/terrain_gen.hpp): literal heights pinned, the relief spanned
// exactly, each style's shape (ridges, terraces with cliffs, flat), the thesis's size, and
// parameters out of range refused naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <set>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "generators/terrain_gen.hpp"

namespace cullcheck::generators {
namespace {

TerrainParams small(const std::string& style) {
  TerrainParams p;
  p.nx = 33, p.ny = 21, p.spacing = 10, p.style = style, p.relief = 100, p.base = 50;
  return p;
}

TEST(TerrainGen, SeededHeightsArePinned) {
  const Terrain t = generate_terrain(small("fractal"), 7);
  ASSERT_EQ(t.vertex_count(), 33u * 21u);
  EXPECT_EQ(t.z[0], 72.229977000193344);
  EXPECT_EQ(t.z[t.index(16, 10)], 81.088819841334583);
  EXPECT_EQ(t.z[t.index(32, 20)], 100.58504113481305);
  EXPECT_EQ(t.z[t.index(5, 17)], 133.49893413470545);
  EXPECT_EQ(t.corner, (Vec2{-160, -100}));
  EXPECT_NE(generate_terrain(small("fractal"), 8).z, t.z);
}

TEST(TerrainGen, EveryStyleSpansItsReliefFromItsBase) {
  for (const char* style : {"fractal", "ridged", "terraces"}) {
    const Terrain t = generate_terrain(small(style), 3);
    const auto [lo, hi] = std::minmax_element(t.z.begin(), t.z.end());
    EXPECT_EQ(*lo, 50.0) << style;
    EXPECT_EQ(*hi, 150.0) << style;
    EXPECT_NO_THROW(validate(t));
    EXPECT_NE(t.source.find(style), std::string::npos) << t.source;
  }
  const Terrain flat = generate_terrain(small("flat"), 3);
  EXPECT_TRUE(std::all_of(flat.z.begin(), flat.z.end(), [](double z) { return z == 50.0; }));
}

TEST(TerrainGen, TerracesAreBenchesJoinedByOneCellCliffs) {
  TerrainParams p = small("terraces");
  p.steps = 5;
  const Terrain t = generate_terrain(p, 3);
  const std::set<double> levels(t.z.begin(), t.z.end());
  EXPECT_EQ(levels, (std::set<double>{50, 75, 100, 125, 150}));
  // A cliff: neighbours a whole level (25 m over 10 m) or more apart.
  double steepest = 0;
  for (std::uint32_t j = 0; j < t.ny; ++j)
    for (std::uint32_t i = 0; i + 1 < t.nx; ++i) steepest = std::max(steepest, std::abs(t.z[t.index(i + 1, j)] - t.z[t.index(i, j)]));
  EXPECT_GE(steepest, 25.0);
}

TEST(TerrainGen, RidgesFoldTheFieldAboutItsMiddle) {
  // The fold maps the fractal field's middle value to the top: the ridged terrain's highest
  // vertex is where the fractal one is nearest its median height, not at its peak.
  const Terrain fractal = generate_terrain(small("fractal"), 5), ridged = generate_terrain(small("ridged"), 5);
  const auto peak = std::max_element(fractal.z.begin(), fractal.z.end()) - fractal.z.begin();
  EXPECT_EQ(ridged.z[std::size_t(peak)], 50.0);  // the fractal peak folds to the floor
  const auto low = std::min_element(fractal.z.begin(), fractal.z.end()) - fractal.z.begin();
  EXPECT_EQ(ridged.z[std::size_t(low)], 50.0);  // and so does its lowest point
}

TEST(TerrainGen, TheThesisTerrainIsItsSizeAndComesInSeconds) {
  const auto start = std::chrono::steady_clock::now();
  const Terrain t = generate_terrain(thesis_terrain_params(), 1);
  const double seconds = seconds_since(start);
  std::printf("the thesis's terrain: %zu triangles, %.1f x %.1f km, generated in %.2f s\n", t.triangle_count(),
              (t.nx - 1) * t.dx / 1000, (t.ny - 1) * t.dy / 1000, seconds);
  EXPECT_EQ(t.triangle_count(), 4959000u);  // "about 4.96 million triangles"
  EXPECT_NEAR((t.nx - 1) * t.dx, 66000.0, 100.0);
  EXPECT_NEAR((t.ny - 1) * t.dy, 56000.0, 100.0);
}

TEST(TerrainGen, HolesAreSeededPerVertexAndLeaveTheHeightsAlone) {
  TerrainParams p = small("ridged");
  EXPECT_TRUE(generate_terrain(p, 7).hole.empty());  // none asked: no flags at all
  p.holes = 0.1;
  const Terrain t = generate_terrain(p, 7);
  ASSERT_EQ(t.hole.size(), t.vertex_count());
  const auto holes = std::count(t.hole.begin(), t.hole.end(), 1);
  EXPECT_EQ(holes, 52);  // of 693 vertices
  EXPECT_EQ(t.present_triangle_count(), 1004u);  // of 1280
  p.holes = 0.0;
  EXPECT_EQ(generate_terrain(p, 7).z, t.z);  // the same heights under the holes
  EXPECT_NO_THROW(validate(t, "terrain"));
}

TEST(TerrainGen, ParametersOutOfRangeAreRefusedNamingTheField) {
  const auto field_of = [](const nlohmann::json& params) {
    try {
      generate_terrain(terrain_params_from_json(params), 1);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string();
  };
  EXPECT_EQ(field_of({{"nx", 9}, {"ny", 9}}), "");
  EXPECT_EQ(field_of({{"nx", 1}}), "nx");
  EXPECT_EQ(field_of({{"ny", 9000}}), "ny");
  EXPECT_EQ(field_of({{"spacing", 0}}), "spacing");
  EXPECT_EQ(field_of({{"roughness", 1.0}}), "roughness");
  EXPECT_EQ(field_of({{"style", "alpine"}}), "style");
  EXPECT_EQ(field_of({{"steps", 1}}), "steps");
  EXPECT_EQ(field_of({{"height", 3}}), "height");  // unknown
  EXPECT_EQ(field_of({{"preset", "moon"}}), "preset");
  EXPECT_EQ(field_of({{"holes", 0.6}}), "holes");
  EXPECT_EQ(terrain_params_from_json({{"preset", "thesis"}, {"relief", 10}}).nx, 1711);
}

}  // namespace
}  // namespace cullcheck::generators
