// CityJSON city models (footprint_formats.hpp) on hand-written files: the transform, ground
// surfaces by semantics and by position, heights from attributes and from the geometry,
// BuildingParts standing for their Building, terrain and other objects skipped and counted; bad
// files, each an InputError naming the field. And the real LoD2 district of The Hague in
// ../shared/data/real/denhaag_lod2, its counts and heights pinned.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/errors.hpp"
#include "core/formats/footprint_formats.hpp"
#include "core/formats/mesh_formats.hpp"

namespace cullcheck::formats {
namespace {

// A box from (x, y, z) to (x + 2, y + 1, z + h) as an LoD2 Solid over vertices 8k..8k+7 (transform
// scale 0.01: integer vertices are hundredths), with or without semantics (the bottom face is the
// sixth, a GroundSurface).
std::string box_vertices(int x, int y, int z, int h) {
  auto v = [&](int dx, int dy, int dz) {
    return "[" + std::to_string((x + dx) * 100) + "," + std::to_string((y + dy) * 100) + "," + std::to_string((z + dz) * 100) + "]";
  };
  return v(0, 0, 0) + "," + v(2, 0, 0) + "," + v(2, 1, 0) + "," + v(0, 1, 0) + "," + v(0, 0, h) + "," + v(2, 0, h) + "," +
         v(2, 1, h) + "," + v(0, 1, h);
}
std::string box_solid(int k, bool semantics) {
  auto i = [&](int n) { return std::to_string(8 * k + n); };
  const std::string faces = "[[" + i(0) + "," + i(1) + "," + i(5) + "," + i(4) + "]],[[" + i(1) + "," + i(2) + "," + i(6) + "," + i(5) +
                            "]],[[" + i(2) + "," + i(3) + "," + i(7) + "," + i(6) + "]],[[" + i(3) + "," + i(0) + "," + i(4) + "," +
                            i(7) + "]],[[" + i(4) + "," + i(5) + "," + i(6) + "," + i(7) + "]],[[" + i(0) + "," + i(3) + "," + i(2) +
                            "," + i(1) + "]]";
  std::string g = R"({"type": "Solid", "lod": 2, "boundaries": [[)" + faces + "]]";
  if (semantics)
    g += R"(, "semantics": {"surfaces": [{"type": "WallSurface"}, {"type": "RoofSurface"}, {"type": "GroundSurface"}],
            "values": [[0, 0, 0, 0, 1, 2]]})";
  return g + "}";
}

std::string city(const std::string& objects, const std::string& vertices, const std::string& extra = "") {
  return R"({"type": "CityJSON", "version": "1.1", "transform": {"scale": [0.01, 0.01, 0.01], "translate": [1000, 2000, 5]},
             "metadata": {"referenceSystem": "https://www.opengis.net/def/crs/EPSG/0/7415"}, )" +
         extra + R"("CityObjects": {)" + objects + R"(}, "vertices": [)" + vertices + "]}";
}

TEST(CityJsonImport, ReadsBuildingsTheirPartsAndTheirGroundThroughTheTransform) {
  // b1: a Building with its own geometry and measuredHeight; b2: a Building of two parts (no
  // semantics: the ground is found at the lowest point); t: terrain; r: a road.
  const std::string objects =
      R"("b1": {"type": "Building", "attributes": {"measuredHeight": 7.5}, "geometry": [)" + box_solid(0, true) + R"(]},
         "b2": {"type": "Building", "children": ["b2-a", "b2-b"]},
         "b2-a": {"type": "BuildingPart", "parents": ["b2"], "geometry": [)" + box_solid(1, false) + R"(]},
         "b2-b": {"type": "BuildingPart", "parents": ["b2"], "geometry": [)" + box_solid(2, true) + R"(]},
         "t": {"type": "TINRelief", "geometry": []},
         "r": {"type": "Road", "geometry": []})";
  const std::string vertices = box_vertices(0, 0, 0, 4) + "," + box_vertices(10, 0, 1, 6) + "," + box_vertices(10, 5, 1, 3);
  ImportReport report;
  const Scene scene = cityjson_from_text(city(objects, vertices), {}, &report);
  ASSERT_EQ(scene.buildings.size(), 3u);
  EXPECT_EQ(report.features, 6u);
  EXPECT_EQ(report.buildings, 3u);
  EXPECT_EQ(report.skipped_not_polygon, 2u) << "the terrain and the road";
  EXPECT_NE(report.crs.find("Amersfoort / RD New"), std::string::npos) << report.crs;
  // Ids follow the objects' ids: b1, b2-a, b2-b.
  EXPECT_DOUBLE_EQ(scene.buildings[0].height, 7.5) << "measuredHeight";
  EXPECT_NEAR(scene.buildings[1].height, 6.0, 1e-9) << "the geometry's own extent";
  EXPECT_NEAR(scene.buildings[2].height, 3.0, 1e-9);
  // Footprints in metres through the transform, counter-clockwise, 2 x 1 m.
  const Box3 b = scene.buildings[1].bounds;
  EXPECT_NEAR(b.hi.x - b.lo.x, 2.0, 1e-9);
  EXPECT_NEAR(b.hi.y - b.lo.y, 1.0, 1e-9);
  EXPECT_NEAR(b.lo.x - scene.buildings[0].bounds.lo.x, 10.0, 1e-9);
  EXPECT_GT(signed_area(scene.buildings[0].footprint), 0.0);
  EXPECT_NEAR(signed_area(scene.buildings[0].footprint), 2.0, 1e-9);
}

TEST(CityJsonImport, AHeightAttributeMustBeThereWhenNamed) {
  const std::string objects = R"("a": {"type": "Building", "attributes": {"RelativeRidgeHeight": "12.5"}, "geometry": [)" +
                              box_solid(0, true) + R"(]}, "b": {"type": "Building", "geometry": [)" + box_solid(1, true) + "]}";
  FootprintOptions o;
  o.height_attribute = "RelativeRidgeHeight";
  ImportReport report;
  const Scene scene = cityjson_from_text(city(objects, box_vertices(0, 0, 0, 4) + "," + box_vertices(5, 0, 0, 4)), o, &report);
  ASSERT_EQ(scene.buildings.size(), 1u);
  EXPECT_DOUBLE_EQ(scene.buildings[0].height, 12.5);
  EXPECT_EQ(report.skipped_no_height, 1u);
  o.missing_height = 3.0;
  const Scene defaulted = cityjson_from_text(city(objects, box_vertices(0, 0, 0, 4) + "," + box_vertices(5, 0, 0, 4)), o, &report);
  ASSERT_EQ(defaulted.buildings.size(), 2u);
  EXPECT_DOUBLE_EQ(defaulted.buildings[1].height, 3.0);
  EXPECT_EQ(report.heights_defaulted, 1u);
}

TEST(CityJsonImport, BadFilesNameWhatIsWrong) {
  auto message = [](const std::string& text) {
    try {
      cityjson_from_text(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("{").find("is not valid JSON"), std::string::npos);
  EXPECT_NE(message(R"({"type": "FeatureCollection"})").find("must be \"CityJSON\""), std::string::npos);
  EXPECT_NE(message(R"({"type": "CityJSON", "version": "3.0", "CityObjects": {}, "vertices": []})").find("version"), std::string::npos);
  const std::string dangling = R"("a": {"type": "Building", "geometry": [)" + box_solid(1, true) + "]}";
  EXPECT_NE(message(city(dangling, box_vertices(0, 0, 0, 4))).find("CityObjects[\"a\"].geometry"), std::string::npos)
      << "a vertex index beyond the vertices";
  EXPECT_NE(message(city(R"("t": {"type": "TINRelief"})", box_vertices(0, 0, 0, 4))).find("none of the 1 city objects became a building"),
            std::string::npos);
  EXPECT_NE(message(R"({"type": "CityJSON", "version": "1.0", "CityObjects": {}, "vertices": [[1, "x", 3]]})").find("vertices[0]"),
            std::string::npos);
  // A geometry without "boundaries" (here misspelt): named, not read out of freed memory (a
  // libFuzzer find, fuzz/regressions/fuzz_cityjson/missing_boundaries.json).
  const std::string misspelt = R"("a": {"type": "Building", "geometry": [{"type": "MultiSurface", "lod": 2, "boendaries": [[[0, 1, 2]]]}]})";
  EXPECT_NE(message(city(misspelt, box_vertices(0, 0, 0, 4))).find("has no boundaries array"), std::string::npos);
}

TEST(CityJsonImport, TheHagueLod2District) {
  const std::string path = std::string(CULLCHECK_SHARED_DATA) + "/real/denhaag_lod2/DenHaag_01.city.json";
  if (!std::filesystem::exists(path)) GTEST_FAIL() << "the real data is missing: " << path;
  ImportReport report;
  const Scene scene = read_scene_file_any(path, {}, &report);
  // 844 Buildings (337 with geometry, 507 of parts) and 1,653 BuildingParts: 1,990 LoD2 solids,
  // one ground surface each; the TINRelief left out.
  EXPECT_EQ(report.features, 2498u);
  EXPECT_EQ(scene.buildings.size(), 1990u);
  EXPECT_EQ(report.skipped_not_polygon, 1u);
  EXPECT_EQ(report.skipped_invalid, 0u);
  EXPECT_EQ(report.parts_split, 0u);
  double tallest = 0.0, total = 0.0;
  for (const Building& b : scene.buildings) tallest = std::max(tallest, b.height), total += b.height;
  EXPECT_NEAR(tallest, 25.071, 1e-6) << "the geometry's extent, as RelativeRidgeHeight's largest";
  EXPECT_NEAR(total / 1990.0, 6.764, 1e-3);
  const Box3 bounds = scene.bounds();
  EXPECT_NEAR(bounds.hi.x - bounds.lo.x, 677.846, 1e-3);
  EXPECT_NEAR(bounds.hi.y - bounds.lo.y, 615.598, 1e-3);
}

TEST(CityJsonImport, KeepsTheSurfacesAsMeshesWhenAsked) {
  const std::string objects =
      R"("b1": {"type": "Building", "geometry": [)" + box_solid(0, true) + R"(]},
         "b2": {"type": "Building", "children": ["b2-a"]},
         "b2-a": {"type": "BuildingPart", "parents": ["b2"], "geometry": [)" + box_solid(1, false) + R"(]})";
  FootprintOptions options;
  options.cityjson_meshes = true;
  ImportReport report;
  const Scene scene = cityjson_from_text(city(objects, box_vertices(0, 0, 0, 4) + "," + box_vertices(10, 0, 1, 6)), options, &report);
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_TRUE(scene.buildings.empty());
  EXPECT_EQ(report.meshes_kept, 2u);
  const MeshObject& b1 = scene.meshes[0];
  EXPECT_EQ(b1.name, "b1");
  EXPECT_EQ(b1.triangles.size(), 12u);
  EXPECT_EQ(b1.vertices.size(), 8u);
  EXPECT_TRUE(b1.closed) << "the solid's six faces share their edges";
  // Each mesh stands on z = 0 (b2-a's box starts 1 m up): 4 and 6 m tall.
  EXPECT_DOUBLE_EQ(b1.bounds.lo.z, 0.0);
  EXPECT_DOUBLE_EQ(b1.bounds.hi.z, 4.0);
  EXPECT_DOUBLE_EQ(scene.meshes[1].bounds.lo.z, 0.0);
  EXPECT_DOUBLE_EQ(scene.meshes[1].bounds.hi.z, 6.0);
  EXPECT_DOUBLE_EQ(scene.meshes[1].bounds.lo.x - b1.bounds.lo.x, 10.0);
}

TEST(CityJsonImport, JoinsABuildingsPartsIntoOneMeshWhenAsked) {
  // b2 is a part, b2-a, with a part b2-b on it, which has a part b2-b-1 on it; b1 stands alone.
  const std::string objects =
      R"("b1": {"type": "Building", "geometry": [)" + box_solid(0, true) + R"(]},
         "b2": {"type": "Building", "children": ["b2-a", "b2-b"]},
         "b2-a": {"type": "BuildingPart", "parents": ["b2"], "geometry": [)" + box_solid(1, false) + R"(]},
         "b2-b": {"type": "BuildingPart", "parents": ["b2"], "children": ["b2-b-1"], "geometry": [)" + box_solid(2, false) + R"(]},
         "b2-b-1": {"type": "BuildingPart", "parents": ["b2-b"], "geometry": [)" + box_solid(3, false) + R"(]})";
  FootprintOptions options;
  options.cityjson_buildings = true;
  ImportReport report;
  const Scene scene = cityjson_from_text(
      city(objects, box_vertices(0, 0, 0, 4) + "," + box_vertices(10, 0, 1, 3) + "," + box_vertices(10, 0, 4, 2) + "," + box_vertices(10, 0, 6, 1)),
      options, &report);
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(report.meshes_kept, 2u);
  const MeshObject& b2 = scene.meshes[1];
  EXPECT_EQ(b2.name, "b2") << "named by its Building";
  EXPECT_EQ(b2.triangles.size(), 36u) << "three parts' solids";
  EXPECT_EQ(b2.vertices.size(), 24u) << "each part on its own vertices";
  EXPECT_TRUE(b2.closed);
  // Lowered as one: b2-a from 0 to 3, b2-b from 3 to 5, b2-b-1 from 5 to 6.
  EXPECT_DOUBLE_EQ(b2.bounds.lo.z, 0.0);
  EXPECT_DOUBLE_EQ(b2.bounds.hi.z, 6.0);
  bool noted = false;
  for (const std::string& n : report.notes) noted = noted || n.find("2 BuildingParts joined") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(CityJsonImport, TheHagueLod2DistrictAsMeshes) {
  const std::string path = std::string(CULLCHECK_SHARED_DATA) + "/real/denhaag_lod2/DenHaag_01.city.json";
  if (!std::filesystem::exists(path)) GTEST_FAIL() << "the real data is missing: " << path;
  ImportOptions options;
  options.footprints.cityjson_meshes = true;
  ImportReport report;
  const Scene scene = read_scene_file_any(path, options, &report);
  EXPECT_EQ(scene.meshes.size(), 1990u) << "one mesh per solid, as one prism per solid";
  EXPECT_TRUE(scene.buildings.empty());
  std::size_t closed = 0;
  double tallest = 0.0;
  for (const MeshObject& m : scene.meshes) closed += m.closed ? 1 : 0, tallest = std::max(tallest, m.bounds.hi.z);
  EXPECT_EQ(scene.triangle_count(), 35592u);
  EXPECT_EQ(closed, 1988u) << "all but two solids share every edge of their surfaces";
  EXPECT_NEAR(tallest, 25.071, 1e-6) << "as the prisms' tallest: each object stands on z = 0";

  options.footprints.cityjson_buildings = true;
  const Scene buildings = read_scene_file_any(path, options, &report);
  EXPECT_EQ(buildings.meshes.size(), 844u) << "one mesh per Building, its parts joined";
  EXPECT_EQ(buildings.triangle_count(), 35592u);
  closed = 0;
  for (const MeshObject& m : buildings.meshes) closed += m.closed ? 1 : 0;
  EXPECT_EQ(closed, 843u) << "the two open solids are parts of one building";
}

}  // namespace
}  // namespace cullcheck::formats
