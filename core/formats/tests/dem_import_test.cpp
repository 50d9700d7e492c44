// Elevation models (dem_reader.hpp): hand-written ESRI ASCII grids in a projected CRS (kept as
// they are, rebased, rows turned south-first, NoData filled or masked, windows and decimation),
// bad files each an InputError naming the field; and the real SRTM tile of Mt Rainier and the
// USGS grid of Jacksboro (../shared/data/real), geographic and so resampled onto metres: their
// extents checked against the WGS84 ellipsoid's own arc lengths (computed here, not by PROJ),
// the summit where the map has it, the GeoTIFF and the ASCII grid agreeing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/formats/dem_reader.hpp"

namespace cullcheck::formats {
namespace {

const std::string kRainier = std::string(CULLCHECK_SHARED_DATA) + "/real/dem_mt_rainier/mt_rainier_90m";
const std::string kJacksboro = std::string(CULLCHECK_SHARED_DATA) + "/real/dem_jacksboro/jacksboro_fault_dem";

// Writes an ESRI ASCII grid (rows north first, as the format has them) and returns its path.
std::string ascii_grid(const std::string& name, const std::vector<std::vector<double>>& rows, double x_corner, double y_corner,
                       double cell, const std::string& nodata = "") {
  const std::string path = (std::filesystem::temp_directory_path() / ("cullcheck_dem_" + name + ".asc")).string();
  std::ofstream out(path);
  out.precision(17);
  out << "ncols " << rows[0].size() << "\nnrows " << rows.size() << "\nxllcorner " << x_corner << "\nyllcorner " << y_corner
      << "\ncellsize " << cell << "\n";
  if (!nodata.empty()) out << "NODATA_value " << nodata << "\n";
  for (const auto& row : rows) {
    for (double v : row) out << v << " ";
    out << "\n";
  }
  return path;
}

std::string dem_error_of(const std::string& path, const DemOptions& o) {
  try {
    read_dem(path, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

DemOptions utm() {
  DemOptions o;
  o.crs = "EPSG:32610";  // WGS 84 / UTM zone 10N
  return o;
}

// 3 x 4 cells of 10 m, the south-west corner at (500000, 5200000): cell centres from
// (500005, 5200005); rows are written north first.
const std::vector<std::vector<double>> kSmall = {{1, 2, 3, 4}, {5, 6, 7, 8}, {9, 10, 11, 12}};

TEST(DemImport, AProjectedGridIsKeptRebasedWithItsSouthRowFirst) {
  const DemImport d = read_dem(ascii_grid("small", kSmall, 500000, 5200000, 10), utm());
  const Terrain& t = d.terrain;
  ASSERT_EQ(t.nx, 4u);
  ASSERT_EQ(t.ny, 3u);
  EXPECT_EQ(t.dx, 10.0);
  EXPECT_EQ(t.dy, 10.0);
  EXPECT_FALSE(d.geographic);
  EXPECT_NE(d.crs_name.find("UTM zone 10N"), std::string::npos) << d.crs_name;
  // Centres 500005..500035 and 5200005..5200025: the whole-metre origin nearest their middle.
  EXPECT_EQ(d.origin.x, 500020.0);
  EXPECT_EQ(d.origin.y, 5200015.0);
  EXPECT_EQ(t.corner.x, -15.0);
  EXPECT_EQ(t.corner.y, -10.0);
  EXPECT_EQ(t.z[t.index(0, 0)], 9.0);   // south-west
  EXPECT_EQ(t.z[t.index(3, 0)], 12.0);  // south-east
  EXPECT_EQ(t.z[t.index(0, 2)], 1.0);   // north-west
  EXPECT_EQ(t.height_at({-15.0 + 10.0, 0.0}), 6.0);
  EXPECT_TRUE(t.hole.empty());
  EXPECT_EQ(d.nodata_cells, 0u);
}

TEST(DemImport, NoDataIsFilledFromItsNeighboursOrKeptAsAHole) {
  std::vector<std::vector<double>> rows = {{1, 2, 3, 4}, {5, -9999, 7, 8}, {9, 10, 11, 12}};
  const std::string path = ascii_grid("hole", rows, 500000, 5200000, 10, "-9999");
  const DemImport filled = read_dem(path, utm());
  EXPECT_EQ(filled.nodata_cells, 1u);
  EXPECT_EQ(filled.filled, 1u);
  EXPECT_TRUE(filled.terrain.hole.empty());
  EXPECT_EQ(filled.terrain.z[filled.terrain.index(1, 1)], (2.0 + 5 + 7 + 10) / 4);  // its four neighbours' mean
  DemOptions o = utm();
  o.nodata = NoData::mask;
  const DemImport masked = read_dem(path, o);
  const Terrain& t = masked.terrain;
  EXPECT_EQ(masked.holes, 1u);
  ASSERT_EQ(t.hole.size(), t.vertex_count());
  EXPECT_TRUE(t.is_hole(t.index(1, 1)));
  // An inner vertex touches six triangles; all six are gone.
  EXPECT_EQ(t.present_triangle_count(), t.triangle_count() - 6);
  EXPECT_TRUE(std::isnan(t.height_at({-5.0, 0.0})));
  EXPECT_NE(masked.summary().find("1 vertices kept as holes"), std::string::npos) << masked.summary();
  EXPECT_NE(filled.summary().find("1 vertices filled"), std::string::npos) << filled.summary();
  // A wider void fills from its rim inward, layer by layer.
  rows = {{1, 1, 1, 1, 1}, {1, -9999, -9999, -9999, 1}, {1, -9999, -9999, -9999, 1}, {1, -9999, -9999, -9999, 1}, {1, 1, 1, 1, 5}};
  const DemImport wide = read_dem(ascii_grid("void", rows, 500000, 5200000, 10, "-9999"), utm());
  EXPECT_EQ(wide.filled, 9u);
  const Terrain& w = wide.terrain;
  EXPECT_EQ(w.z[w.index(2, 2)], 1.0);  // the centre: mean of four rim-filled ones, all 1
  EXPECT_EQ(w.z[w.index(3, 1)], 1.0);  // beside the 5 diagonally only: 4-neighbours are 1s
}

TEST(DemImport, AWindowAndAStepKeepEveryStepthCell) {
  std::vector<std::vector<double>> rows(9, std::vector<double>(11));
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 11; ++c) rows[r][c] = 100 * r + c;
  const std::string path = ascii_grid("window", rows, 500000, 5200000, 5);
  DemOptions o = utm();
  o.column = 1, o.row = 2, o.columns = 7, o.rows = 5, o.step = 2;
  const Terrain t = read_dem(path, o).terrain;
  ASSERT_EQ(t.nx, 4u);  // columns 1, 3, 5, 7
  ASSERT_EQ(t.ny, 3u);  // rows 2, 4, 6 (north first), so the south row is row 6
  EXPECT_EQ(t.dx, 10.0);
  EXPECT_EQ(t.dy, 10.0);
  EXPECT_EQ(t.z[t.index(0, 0)], 601.0);
  EXPECT_EQ(t.z[t.index(3, 2)], 207.0);
}

TEST(DemImport, BadFilesAndOptionsAreInputErrorsNamingTheField) {
  const std::string path = ascii_grid("bad", kSmall, 500000, 5200000, 10);
  EXPECT_NE(dem_error_of(path, {}).find("field 'crs'"), std::string::npos) << dem_error_of(path, {});  // no .prj, no override
  DemOptions o = utm();
  o.column = 4;
  EXPECT_NE(dem_error_of(path, o).find("field 'window'"), std::string::npos);
  o = utm();
  o.columns = 9;
  EXPECT_NE(dem_error_of(path, o).find("field 'window'"), std::string::npos);
  o = utm();
  o.step = 0;
  EXPECT_NE(dem_error_of(path, o).find("field 'step'"), std::string::npos);
  o = utm();
  o.step = 3;  // 2 x 1 cells left
  EXPECT_NE(dem_error_of(path, o).find("a terrain needs 2 x 2"), std::string::npos);
  o = utm();
  o.crs = "EPSG:5773";  // a vertical CRS
  EXPECT_NE(dem_error_of(path, o).find("field 'crs'"), std::string::npos);
  EXPECT_NE(dem_error_of("/nonexistent/dem.tif", utm()).find("field 'file'"), std::string::npos);
  const std::string text = (std::filesystem::temp_directory_path() / "cullcheck_dem_text.tif").string();
  std::ofstream(text) << "not a raster\n";
  EXPECT_NE(dem_error_of(text, utm()).find("field 'file'"), std::string::npos);
  const std::string empty = ascii_grid("nodata_only", {{-1, -1}, {-1, -1}}, 0, 0, 1, "-1");
  EXPECT_NE(dem_error_of(empty, utm()).find("no cell of the window has data"), std::string::npos);
}

// WGS84: a = 6378137 m, f = 1/298.257223563.
constexpr double kA = 6378137.0, kE2 = (2 - 1 / 298.257223563) / 298.257223563;
constexpr double kDeg = 3.14159265358979323846 / 180;
double prime_vertical(double lat) { return kA / std::sqrt(1 - kE2 * std::sin(lat * kDeg) * std::sin(lat * kDeg)); }
// The meridian's arc from lat0 to lat1 (degrees), Simpson's rule on 2,000 steps.
double meridian_arc(double lat0, double lat1) {
  const auto m = [](double lat) {
    const double s = std::sin(lat * kDeg);
    return kA * (1 - kE2) / std::pow(1 - kE2 * s * s, 1.5);
  };
  const int n = 2000;
  const double h = (lat1 - lat0) / n;
  double sum = m(lat0) + m(lat1);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * m(lat0 + i * h);
  return sum * h / 3 * kDeg;
}

TEST(DemImport, TheRainierTileIsResampledOntoMetresWithItsSummitInPlace) {
  const DemImport d = read_dem(kRainier + ".tif");
  const Terrain& t = d.terrain;
  EXPECT_TRUE(d.geographic);
  EXPECT_EQ(d.raster_columns, 1201u);
  EXPECT_EQ(d.raster_rows, 1201u);
  ASSERT_EQ(t.nx, 1201u);
  ASSERT_EQ(t.ny, 1201u);
  EXPECT_EQ(d.nodata_cells, 9033u);  // SOURCE.md: the SRTM voids
  EXPECT_EQ(d.filled, 9033u);
  EXPECT_NEAR(d.lon0, -121.5, 1e-9);
  EXPECT_NEAR(d.lat0, 46.5, 1e-9);
  // Cell centres span 1 degree each way (-122..-121, 46..47). The rectangle inside their
  // projected outline is as wide as the 47th parallel's degree (the narrowest) and as tall as
  // the central meridian's degree less the 46th parallel's bulge at its ends, x^2 tan(lat)/2N.
  const double width = prime_vertical(47.0) * std::cos(47.0 * kDeg) * kDeg;
  const double half = 0.5 * width, south_half = 0.5 * prime_vertical(46.0) * std::cos(46.0 * kDeg) * kDeg;
  const double bulge = south_half * south_half * std::tan(46.0 * kDeg) / (2 * prime_vertical(46.0));
  const double height = meridian_arc(46.0, 47.0) - bulge;
  EXPECT_NEAR(t.dx * (t.nx - 1), width, 5.0);
  EXPECT_NEAR(t.dy * (t.ny - 1), height, 5.0);
  EXPECT_NEAR(t.corner.x, -half, 5.0);
  // The summit (46.8529 N, 121.7604 W; 4,392 m surveyed, 4,371 m at most in the tile): the
  // highest vertex lies within a cell or two of where the ellipsoid puts it.
  const auto top = std::max_element(t.z.begin(), t.z.end()) - t.z.begin();
  const double x = t.corner.x + double(top % t.nx) * t.dx, y = t.corner.y + double(top / t.nx) * t.dy;
  const double summit_x = prime_vertical(46.8529) * std::cos(46.8529 * kDeg) * (-121.7604 + 121.5) * kDeg;
  const double summit_y = meridian_arc(46.5, 46.8529);
  EXPECT_NEAR(x, summit_x, 200.0);
  EXPECT_NEAR(y, summit_y, 200.0);
  EXPECT_LE(t.z[top], 4371.0);
  EXPECT_GT(t.z[top], 4250.0);
  EXPECT_GE(*std::min_element(t.z.begin(), t.z.end()), 263.0);
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return HUGE_VAL;
  double most = 0;
  for (std::size_t i = 0; i < a.size(); ++i) most = std::max(most, std::abs(a[i] - b[i]));
  return most;
}

TEST(DemImport, RealGridsReadTheSameFromGeoTiffAndAsciiAndMaskTheirVoids) {
  DemOptions o;
  o.column = 500, o.row = 200, o.columns = 300, o.rows = 300;  // the summit's neighbourhood
  const DemImport tif = read_dem(kRainier + ".tif", o), asc = read_dem(kRainier + ".asc", o);
  // The .asc writes the cell size to 12 decimals (0.000833333333 for 1/1200 degree), so its grid
  // sits up to a millimetre off the GeoTIFF's, and the resampled heights differ by less than that.
  EXPECT_NEAR(tif.terrain.dx, asc.terrain.dx, 1e-5);
  EXPECT_LT(largest_difference(tif.terrain.z, asc.terrain.z), 0.01);
  EXPECT_GT(tif.nodata_cells, 0u);
  o.nodata = NoData::mask;
  const DemImport masked = read_dem(kRainier + ".tif", o);
  EXPECT_EQ(masked.nodata_cells, tif.nodata_cells);
  EXPECT_GE(masked.holes, masked.nodata_cells);  // a void cell spoils the vertices interpolated from it
  EXPECT_LT(masked.terrain.present_triangle_count(), masked.terrain.triangle_count());
  const DemImport j = read_dem(kJacksboro + ".tif"), ja = read_dem(kJacksboro + ".asc");
  EXPECT_EQ(j.terrain.nx, 403u);
  EXPECT_EQ(j.terrain.ny, 344u);
  EXPECT_EQ(j.nodata_cells, 0u);
  EXPECT_LT(largest_difference(j.terrain.z, ja.terrain.z), 0.01);
  // 3 arc-seconds at 36.6 N: about 74 m east-west, 92.5 m north-south (SOURCE.md).
  EXPECT_NEAR(j.terrain.dx, 74.4, 0.5);
  EXPECT_NEAR(j.terrain.dy, 92.5, 0.5);
  const auto [lo, hi] = std::minmax_element(j.terrain.z.begin(), j.terrain.z.end());
  EXPECT_GE(*lo, 236.0);
  EXPECT_LE(*hi, 1076.0);
}

}  // namespace
}  // namespace cullcheck::formats
