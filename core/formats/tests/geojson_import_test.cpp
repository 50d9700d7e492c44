// GeoJSON footprints (footprint_formats.hpp) on hand-written files: heights from storeys or
// metres, MultiPolygon parts, holes, repaired and skipped rings, features without a footprint or
// a height, every count of the import report; longitude/latitude projected to metres, checked
// against the WGS84 ellipsoid's own arc lengths (computed here, not by PROJ); projected CRSs in
// metres and in US survey feet; bad files, each an InputError naming the field. And the real
// Boston footprints of ../shared/data/real/boston_buildings, with their counts pinned.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/formats/footprint_formats.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

std::string collection(const std::string& features, const std::string& crs = "") {
  return R"({"type": "FeatureCollection", )" + (crs.empty() ? "" : R"("crs": {"type": "name", "properties": {"name": ")" + crs + R"("}}, )") +
         R"("features": [)" + features + "]}";
}
std::string feature(const std::string& properties, const std::string& geometry) {
  return R"({"type": "Feature", "properties": )" + properties + R"(, "geometry": )" + geometry + "}";
}
std::string polygon(const std::string& rings) { return R"({"type": "Polygon", "coordinates": [)" + rings + "]}"; }
// A closed square ring with corner (x, y) and side s.
std::string square(double x, double y, double s) {
  std::ostringstream r;
  r.precision(17);
  r << "[[" << x << "," << y << "],[" << x + s << "," << y << "],[" << x + s << "," << y + s << "],[" << x << "," << y + s
    << "],[" << x << "," << y << "]]";
  return r.str();
}

FootprintOptions storeys(double storey = 3.5) {
  FootprintOptions o;
  o.storeys_attribute = "floors";
  o.storey_height = storey;
  o.crs = "local";
  return o;
}

double edge(const Building& b, std::size_t i) { return length(b.footprint[(i + 1) % b.footprint.size()] - b.footprint[i]); }

TEST(GeoJsonImport, StoreysTimesStoreyHeightNumberedInFileOrder) {
  ImportReport report;
  const Scene s = geojson_from_text(collection(feature(R"({"floors": 3})", polygon(square(0, 0, 10))) + "," +
                                               feature(R"({"floors": "2.5"})", polygon(square(20, 0, 5)))),
                                    storeys(3.0), &report);
  ASSERT_EQ(s.buildings.size(), 2u);
  EXPECT_EQ(s.buildings[0].id, 0u);
  EXPECT_EQ(s.buildings[1].id, 1u);
  EXPECT_DOUBLE_EQ(s.buildings[0].height, 9.0);
  EXPECT_DOUBLE_EQ(s.buildings[1].height, 7.5);
  EXPECT_EQ(s.buildings[0].footprint.size(), 4u);  // the closing vertex is not kept
  EXPECT_DOUBLE_EQ(s.buildings[1].bounds.lo.x, 20.0);
  EXPECT_EQ(report.features, 2u);
  EXPECT_EQ(report.buildings, 2u);
  EXPECT_EQ(report.objects, 2u);
  EXPECT_EQ(report.rings_repaired, 0u);
  EXPECT_NE(report.crs.find("local metres"), std::string::npos) << report.crs;
}

TEST(GeoJsonImport, HeightAttributeInMetresOrTheDefaultHeightAttribute) {
  FootprintOptions o;
  o.height_attribute = "h";
  o.crs = "local";
  const Scene a = geojson_from_text(collection(feature(R"({"h": 12.25})", polygon(square(0, 0, 4)))), o);
  ASSERT_EQ(a.buildings.size(), 1u);
  EXPECT_DOUBLE_EQ(a.buildings[0].height, 12.25);
  o.height_attribute.clear();  // neither flag: "height" in metres
  const Scene b = geojson_from_text(collection(feature(R"({"height": 6})", polygon(square(0, 0, 4)))), o);
  ASSERT_EQ(b.buildings.size(), 1u);
  EXPECT_DOUBLE_EQ(b.buildings[0].height, 6.0);
}

TEST(GeoJsonImport, MultiPolygonPartsAreBuildingsAndHolesAreCounted) {
  ImportReport report;
  const std::string multi = R"({"type": "MultiPolygon", "coordinates": [[)" + square(0, 0, 10) + "," + square(3, 3, 2) + "],[" +
                            square(30, 0, 4) + "]]}";
  const Scene s = geojson_from_text(collection(feature(R"({"floors": 2})", multi)), storeys(), &report);
  ASSERT_EQ(s.buildings.size(), 2u);
  EXPECT_DOUBLE_EQ(s.buildings[0].height, 7.0);
  EXPECT_DOUBLE_EQ(s.buildings[1].height, 7.0);
  EXPECT_DOUBLE_EQ(s.buildings[1].bounds.lo.x, 30.0);
  EXPECT_EQ(report.parts_split, 1u);
  EXPECT_EQ(report.holes_filled, 1u);
  // The hole is roofed over: the footprint is the outer ring, 10 x 10.
  EXPECT_DOUBLE_EQ(signed_area(s.buildings[0].footprint), 100.0);
}

TEST(GeoJsonImport, RepeatedVerticesAndSpikesAreRepairedAndCrossingRingsSkippedByName) {
  ImportReport report;
  // A square with a repeated corner and a spike (out to (15, 5) and straight back) on its right side.
  const std::string repaired = "[[0,0],[10,0],[10,0],[10,5],[15,5],[10,5],[10,10],[0,10],[0,0]]";
  const std::string bow_tie = "[[0,0],[10,10],[10,0],[0,10],[0,0]]";
  const Scene s = geojson_from_text(collection(feature(R"({"floors": 1})", polygon(repaired)) + "," +
                                               feature(R"({"floors": 1})", polygon(bow_tie)) + "," +
                                               feature(R"({"floors": 1})", polygon("[[0,0],[1,1],[0,0]]"))),
                                    storeys(), &report);
  ASSERT_EQ(s.buildings.size(), 1u);
  EXPECT_EQ(s.buildings[0].footprint.size(), 5u);  // (10, 5) stays, collinear; the spike and the repeat go
  EXPECT_DOUBLE_EQ(signed_area(s.buildings[0].footprint), 100.0);
  EXPECT_EQ(report.rings_repaired, 1u);
  EXPECT_EQ(report.skipped_invalid, 2u);
  ASSERT_EQ(report.notes.size(), 2u);
  EXPECT_NE(report.notes[0].find("features[1]: footprint edges cross or touch"), std::string::npos) << report.notes[0];
  EXPECT_NE(report.notes[1].find("features[2]: footprint fewer than 3 distinct vertices"), std::string::npos) << report.notes[1];
}

TEST(GeoJsonImport, FeaturesWithoutAHeightAreSkippedOrGivenTheMissingHeight) {
  const std::string file = collection(feature(R"({"floors": 0})", polygon(square(0, 0, 5))) + "," +
                                      feature(R"({"floors": "n/a"})", polygon(square(10, 0, 5))) + "," +
                                      feature(R"({})", polygon(square(20, 0, 5))) + "," +
                                      feature(R"({"floors": 4})", polygon(square(30, 0, 5))));
  ImportReport skipped;
  const Scene a = geojson_from_text(file, storeys(), &skipped);
  ASSERT_EQ(a.buildings.size(), 1u);
  EXPECT_DOUBLE_EQ(a.buildings[0].height, 14.0);
  EXPECT_EQ(skipped.skipped_no_height, 3u);
  EXPECT_EQ(skipped.heights_defaulted, 0u);
  FootprintOptions o = storeys();
  o.missing_height = 3.5;
  ImportReport defaulted;
  const Scene b = geojson_from_text(file, o, &defaulted);
  ASSERT_EQ(b.buildings.size(), 4u);
  EXPECT_DOUBLE_EQ(b.buildings[0].height, 3.5);
  EXPECT_EQ(defaulted.skipped_no_height, 0u);
  EXPECT_EQ(defaulted.heights_defaulted, 3u);
}

TEST(GeoJsonImport, FeaturesThatAreNoFootprintAreSkippedAndCounted) {
  ImportReport report;
  const Scene s = geojson_from_text(collection(feature(R"({"floors": 1})", R"({"type": "Point", "coordinates": [1, 2]})") + "," +
                                               feature(R"({"floors": 1})", "null") + "," +
                                               feature(R"({"floors": 1})", polygon(square(0, 0, 3)))),
                                    storeys(), &report);
  EXPECT_EQ(s.buildings.size(), 1u);
  EXPECT_EQ(report.skipped_not_polygon, 2u);
  EXPECT_EQ(report.features, 3u);
}

std::string error_of(const std::string& text, const FootprintOptions& o = storeys()) {
  try {
    geojson_from_text(text, o, nullptr, "file bad.geojson");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GeoJsonImport, BadFilesAreInputErrorsNamingTheField) {
  struct Case {
    std::string text, expect;
  };
  const std::vector<Case> cases = {
      {"{", "is not valid JSON"},
      {R"({"type": "Topology"})", "field 'type'"},
      {R"({"type": "FeatureCollection", "features": 3})", "field 'features'"},
      {collection(R"({"type": "Feature", "properties": {}, "geometry": {"type": "Polygon"}})"),
       "features[0].geometry.coordinates"},
      {collection(feature(R"({"floors": 1})", polygon(R"([[0,0],["a",1],[1,1],[0,0]])"))),
       "features[0].geometry.coordinates[0][1]"},
      {collection(feature(R"({"floors": 1})", polygon("[[0,0],[2e9,0],[0,1],[0,0]]"))), "beyond 1e9 m"},
      {collection(R"({"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": 7}})"),
       "array of linear rings"},
  };
  for (const Case& c : cases) {
    const std::string got = error_of(c.text);
    EXPECT_NE(got.find("bad.geojson"), std::string::npos) << c.text << " -> " << got;
    EXPECT_NE(got.find(c.expect), std::string::npos) << c.text << " -> " << got;
  }
  // Every feature skipped (here: no "floors") is an error, not an empty city.
  EXPECT_NE(error_of(collection(feature(R"({"levels": 3})", polygon(square(0, 0, 5))))).find("none of the 1 features"),
            std::string::npos);
  FootprintOptions both = storeys();
  both.height_attribute = "h";
  EXPECT_NE(error_of(collection(""), both).find("exclude each other"), std::string::npos);
  FootprintOptions unknown = storeys();
  unknown.crs = "EPSG:99999999";
  EXPECT_NE(error_of(collection(feature(R"({"floors": 1})", polygon(square(0, 0, 1)))), unknown).find("PROJ knows"),
            std::string::npos);
}

// RFC 7946's default: longitude/latitude on WGS84. A 0.001 x 0.001 degree cell at 42 N, 71 W.
TEST(GeoJsonImport, LongitudeLatitudeIsProjectedToLocalMetres) {
  FootprintOptions o = storeys();
  o.crs.clear();
  ImportReport report;
  const Scene s = geojson_from_text(collection(feature(R"({"floors": 1})", polygon("[[-71.0,42.0],[-70.999,42.0],[-70.999,42.001],[-71.0,42.001],[-71.0,42.0]]"))),
                                    o, &report);
  ASSERT_EQ(s.buildings.size(), 1u);
  const Building& b = s.buildings[0];
  // The ellipsoid's arc lengths (a = 6378137 m, f = 1/298.257223563): the parallel's at 42 and
  // 42.001 N, the meridian's between them; the transverse Mercator at the cell's centre keeps
  // them to well under a millimetre.
  EXPECT_NEAR(edge(b, 0), 82.85076, 1e-3);
  EXPECT_NEAR(edge(b, 1), 111.07329, 1e-3);
  EXPECT_NEAR(edge(b, 2), 82.84946, 1e-3);
  EXPECT_NEAR(edge(b, 3), 111.07329, 1e-3);
  // Centred: the cell's centre is the projection's origin.
  EXPECT_NEAR(b.bounds.lo.x + b.bounds.hi.x, 0.0, 1e-3);
  EXPECT_NE(report.crs.find("transverse Mercator"), std::string::npos) << report.crs;
}

TEST(GeoJsonImport, ProjectedCrsIsTakenAsItIsTimesItsUnitAndRebased) {
  FootprintOptions o = storeys();
  o.crs.clear();
  ImportReport report;
  const Scene utm = geojson_from_text(
      collection(feature(R"({"floors": 2})", polygon(square(329000.5, 4691000.25, 20))), "urn:ogc:def:crs:EPSG::26919"), o, &report);
  ASSERT_EQ(utm.buildings.size(), 1u);
  EXPECT_DOUBLE_EQ(edge(utm.buildings[0], 0), 20.0);
  // UTM coordinates are far from the origin: the scene is rebased onto a whole-metre origin.
  EXPECT_EQ(utm.origin.x, 329011.0);
  EXPECT_EQ(utm.origin.y, 4691010.0);
  EXPECT_DOUBLE_EQ(utm.buildings[0].bounds.lo.x + utm.origin.x, 329000.5);
  EXPECT_NE(report.crs.find("UTM zone 19N"), std::string::npos) << report.crs;
  // NAD83 / Massachusetts Mainland in US survey feet: 100 ftUS = 30.480061 m.
  const Scene feet = geojson_from_text(collection(feature(R"({"floors": 2})", polygon(square(700000, 2900000, 100))), "EPSG:2249"), o);
  ASSERT_EQ(feet.buildings.size(), 1u);
  EXPECT_NEAR(edge(feet.buildings[0], 0), 30.480061, 1e-6);
}

TEST(GeoJsonImport, MetresInAFileThatNamesNoCrsAskForOne) {
  FootprintOptions o = storeys();
  o.crs.clear();
  const std::string got = error_of(collection(feature(R"({"floors": 2})", polygon(square(329000, 4691000, 20)))), o);
  EXPECT_NE(got.find("--crs"), std::string::npos) << got;
}

TEST(GeoJsonImport, JsonFilesAreReadAsGeoJsonWhenTheySaySo) {
  const std::string path = (std::filesystem::temp_directory_path() / "cullcheck_footprints_test.json").string();
  {
    std::ofstream out(path);
    out << collection(feature(R"({"floors": 2})", polygon(square(0, 0, 8))));
  }
  ImportOptions options;
  options.footprints = storeys();
  ImportReport report;
  const Scene s = read_scene_file_any(path, options, &report);
  ASSERT_EQ(s.buildings.size(), 1u);
  EXPECT_DOUBLE_EQ(s.buildings[0].height, 7.0);
  EXPECT_EQ(report.features, 1u);
  std::filesystem::remove(path);
}

// The real thing: 22,187 footprints of central Boston (SOURCE.md beside the file), storey counts
// in story_ht_, 3,994 of them 0 (unknown). The counts below are pinned from the first import and
// agree with SOURCE.md where it states them (features, the 47 polygons with holes, 62 storeys at
// most). A change to the reader's repair rules shows here.
TEST(GeoJsonImport, RealBostonFootprints) {
  const std::string path = std::string(CULLCHECK_SHARED_DATA) + "/real/boston_buildings/boston_buildings_utm19n.geojson";
  ASSERT_TRUE(std::filesystem::exists(path)) << "the real data is not beside the checkout: " << path;
  FootprintOptions o;
  o.storeys_attribute = "story_ht_";
  o.missing_height = 3.5;
  ImportReport report;
  const Scene s = read_geojson(path, o, &report);
  EXPECT_EQ(report.features, 22187u);
  EXPECT_EQ(report.skipped_not_polygon, 0u);
  EXPECT_EQ(report.skipped_no_height, 0u);
  EXPECT_EQ(report.heights_defaulted, 3994u);
  EXPECT_EQ(report.buildings + report.skipped_invalid, 22187u);
  EXPECT_EQ(report.buildings, s.buildings.size());
  // Pinned: 8 footprints whose edges cross or touch and 1 left with 2 vertices (SOURCE.md: GEOS
  // finds 9 invalid); 130 rings lose repeated vertices or spikes; 60 inner rings in 47 polygons.
  EXPECT_EQ(report.buildings, 22178u);
  EXPECT_EQ(report.skipped_invalid, 9u);
  EXPECT_EQ(report.rings_repaired, 130u);
  EXPECT_EQ(report.holes_filled, 60u);
  EXPECT_EQ(report.parts_split, 0u);
  ASSERT_FALSE(report.notes.empty());
  EXPECT_EQ(report.notes.front(), "features[510]: footprint edges cross or touch, skipped");
  double tallest = 0.0;
  for (const Building& b : s.buildings) tallest = std::max(tallest, b.height);
  EXPECT_DOUBLE_EQ(tallest, 62 * 3.5);
  EXPECT_NE(report.crs.find("UTM zone 19N"), std::string::npos) << report.crs;
  const Box3 box = s.bounds();
  EXPECT_NEAR(box.lo.x + s.origin.x, 326354.2, 0.1);
  EXPECT_NEAR(box.hi.y + s.origin.y, 4693914.0, 0.1);
}

}  // namespace
}  // namespace cullcheck::formats
