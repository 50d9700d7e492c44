// GDAL behind dem_reader.hpp: the raster's band, geotransform and CRS are read here; the CRS's
// kind and the transverse Mercator go through crs_projection.hpp (PROJ).
#include "core/formats/dem_reader.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <sstream>
#include <vector>

#include "core/errors.hpp"
#include "core/formats/crs_projection.hpp"

namespace cullcheck::formats {
namespace {

// The raster window as read: heights row-major from the window's north row, with its cells'
// validity, and the positions of its cell centres in the raster's CRS units.
struct Window {
  std::size_t columns = 0, rows = 0;
  std::vector<double> z;
  std::vector<std::uint8_t> valid;
  double west = 0, north = 0;          // centre of the window's first cell
  double step_x = 0, step_y = 0;       // between kept cell centres (step_y > 0 going south)
};

// GDAL keeps its last error per thread; this scope silences its printing and collects it.
struct QuietGdal {
  QuietGdal() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  static std::string last() {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? m : "no reason given";
  }
};

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};

double unit_to_metres(const std::string& unit, const std::string& path) {
  std::string u = unit;
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (u.empty() || u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters") return 1.0;
  if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return 0.3048;
  if (u == "us survey foot" || u == "ftus" || u == "us_survey_foot") return 1200.0 / 3937.0;
  throw InputError(path, "unit", "heights in '" + unit + "', neither metres nor feet");
}

// Fills every invalid cell, layer by layer from the valid ones: a cell of the next layer takes
// the mean of its 4-neighbours already holding a height. Deterministic: the layers are swept in
// row order and a layer's values are set only after the whole layer is found.
std::size_t fill_nodata(std::vector<double>& z, std::vector<std::uint8_t>& valid, std::size_t nx, std::size_t ny) {
  std::size_t filled = 0;
  std::vector<std::size_t> layer;
  for (;;) {
    layer.clear();
    for (std::size_t v = 0; v < z.size(); ++v) {
      if (valid[v]) continue;
      const std::size_t i = v % nx, j = v / nx;
      if ((i > 0 && valid[v - 1]) || (i + 1 < nx && valid[v + 1]) || (j > 0 && valid[v - nx]) || (j + 1 < ny && valid[v + nx]))
        layer.push_back(v);
    }
    if (layer.empty()) return filled;
    std::vector<double> value(layer.size());
    for (std::size_t k = 0; k < layer.size(); ++k) {
      const std::size_t v = layer[k], i = v % nx, j = v / nx;
      double sum = 0;
      int n = 0;
      if (i > 0 && valid[v - 1]) sum += z[v - 1], ++n;
      if (i + 1 < nx && valid[v + 1]) sum += z[v + 1], ++n;
      if (j > 0 && valid[v - nx]) sum += z[v - nx], ++n;
      if (j + 1 < ny && valid[v + nx]) sum += z[v + nx], ++n;
      value[k] = sum / n;
    }
    for (std::size_t k = 0; k < layer.size(); ++k) z[layer[k]] = value[k], valid[layer[k]] = 1;
    filled += layer.size();
  }
}

}  // namespace

std::string DemImport::summary() const {
  std::ostringstream s;
  s.precision(10);
  s << terrain.nx << " x " << terrain.ny << " vertices " << terrain.dx << " x " << terrain.dy << " m apart from a "
    << raster_columns << " x " << raster_rows << " raster (" << crs_name << ")";
  if (geographic) s << ", resampled onto a transverse Mercator at " << lon0 << ", " << lat0;
  s << "; " << nodata_cells << " NoData cells";
  if (nodata_cells > 0) {
    if (holes > 0 || filled == 0)
      s << ", " << holes << " vertices kept as holes";
    else
      s << ", " << filled << " vertices filled from their neighbours";
  }
  return s.str();
}

DemImport read_dem(const std::string& path, const DemOptions& options) {
  const QuietGdal quiet;
  const std::unique_ptr<GDALDataset, DatasetCloser> ds(
      static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) throw InputError(path, "file", "not a raster GDAL can read (" + QuietGdal::last() + ")");
  if (ds->GetRasterCount() < 1) throw InputError(path, "bands", "the raster has no band");
  DemImport out;
  out.raster_columns = std::size_t(ds->GetRasterXSize());
  out.raster_rows = std::size_t(ds->GetRasterYSize());
  double gt[6];
  if (ds->GetGeoTransform(gt) != CE_None) throw InputError(path, "geotransform", "the raster is not georeferenced");
  if (gt[2] != 0.0 || gt[4] != 0.0) throw InputError(path, "geotransform", "rotated or sheared rasters are not supported");
  if (!(gt[1] > 0.0) || !(gt[5] < 0.0))
    throw InputError(path, "geotransform", "the raster must run west to east and north to south (north up)");

  // The CRS: the override, else the raster's.
  std::string crs = options.crs;
  if (crs.empty()) {
    const OGRSpatialReference* srs = ds->GetSpatialRef();
    if (!srs) throw InputError(path, "crs", "the raster has no CRS (an .asc without its .prj?): give one, or \"local\" for metres");
    char* wkt = nullptr;
    const char* wkt_options[] = {"FORMAT=WKT2_2019", nullptr};
    srs->exportToWkt(&wkt, wkt_options);
    crs = wkt ? wkt : "";
    CPLFree(wkt);
  }
  double metres_per_unit = 1.0;
  if (crs == "local") {
    out.crs_name = "local";
  } else {
    const CrsKind kind = describe_crs(crs, path);
    out.crs_name = kind.name;
    out.geographic = kind.geographic;
    metres_per_unit = kind.metres_per_unit;
  }

  // The window, checked against the raster, then read.
  const std::size_t columns = options.columns ? options.columns : out.raster_columns - std::min(options.column, out.raster_columns);
  const std::size_t rows = options.rows ? options.rows : out.raster_rows - std::min(options.row, out.raster_rows);
  if (options.column >= out.raster_columns || options.row >= out.raster_rows || options.column + columns > out.raster_columns ||
      options.row + rows > out.raster_rows)
    throw InputError(path, "window", "columns " + std::to_string(options.column) + "+" + std::to_string(columns) + ", rows " +
                                         std::to_string(options.row) + "+" + std::to_string(rows) + " lie outside the " +
                                         std::to_string(out.raster_columns) + " x " + std::to_string(out.raster_rows) + " raster");
  if (options.step == 0) throw InputError(path, "step", "must be at least 1");
  Window w;
  w.columns = (columns + options.step - 1) / options.step;
  w.rows = (rows + options.step - 1) / options.step;
  if (w.columns < 2 || w.rows < 2)
    throw InputError(path, "window", "keeps " + std::to_string(w.columns) + " x " + std::to_string(w.rows) + " cells; a terrain needs 2 x 2");
  GDALRasterBand* band = ds->GetRasterBand(1);
  std::vector<double> full(columns * rows);
  if (band->RasterIO(GF_Read, int(options.column), int(options.row), int(columns), int(rows), full.data(), int(columns), int(rows),
                     GDT_Float64, 0, 0) != CE_None)
    throw InputError(path, "band", "cannot read its heights (" + QuietGdal::last() + ")");
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  const double scale = band->GetScale(), offset = band->GetOffset();
  const double z_unit = unit_to_metres(band->GetUnitType() ? band->GetUnitType() : "", path);
  w.z.resize(w.columns * w.rows);
  w.valid.resize(w.z.size());
  for (std::size_t r = 0; r < w.rows; ++r)
    for (std::size_t c = 0; c < w.columns; ++c) {
      const double v = full[r * options.step * columns + c * options.step];
      const bool ok = std::isfinite(v) && !(has_nodata && (v == nodata || (std::isnan(nodata) && std::isnan(v))));
      w.valid[r * w.columns + c] = ok ? 1 : 0;
      w.z[r * w.columns + c] = ok ? (v * scale + offset) * z_unit : 0.0;
    }
  for (std::size_t k = 0; k < full.size(); ++k) {
    const double v = full[k];
    out.nodata_cells += (!std::isfinite(v) || (has_nodata && v == nodata)) ? 1 : 0;
  }
  if (std::find(w.valid.begin(), w.valid.end(), std::uint8_t(1)) == w.valid.end())
    throw InputError(path, "band", "no cell of the window has data");
  w.west = gt[0] + (options.column + 0.5) * gt[1];
  w.north = gt[3] + (options.row + 0.5) * gt[5];
  w.step_x = gt[1] * options.step;
  w.step_y = -gt[5] * options.step;
  std::vector<std::uint8_t> was_valid = w.valid;
  if (options.nodata == NoData::fill) fill_nodata(w.z, w.valid, w.columns, w.rows);

  Terrain& t = out.terrain;
  t.nx = std::uint32_t(w.columns), t.ny = std::uint32_t(w.rows);
  t.z.resize(t.vertex_count());
  const bool masking = options.nodata == NoData::mask && out.nodata_cells > 0;
  if (masking) t.hole.assign(t.vertex_count(), 0);
  if (!out.geographic) {
    // Projected (or local): the grid is regular already. Row 0 of the terrain is the south row.
    t.dx = w.step_x * metres_per_unit, t.dy = w.step_y * metres_per_unit;
    const double east = w.west + (w.columns - 1) * w.step_x, south = w.north - (w.rows - 1) * w.step_y;
    // A whole-metre origin near the window's centre, as footprint imports rebase.
    out.origin = {std::round(0.5 * (w.west + east) * metres_per_unit), std::round(0.5 * (w.north + south) * metres_per_unit)};
    t.corner = {w.west * metres_per_unit - out.origin.x, south * metres_per_unit - out.origin.y};
    for (std::uint32_t j = 0; j < t.ny; ++j)
      for (std::uint32_t i = 0; i < t.nx; ++i) {
        const std::size_t from = (w.rows - 1 - j) * w.columns + i;
        t.z[t.index(i, j)] = w.z[from];
        if (masking) t.hole[t.index(i, j)] = w.valid[from] ? 0 : 1;
      }
  } else {
    // Geographic: resample onto a regular grid of the local transverse Mercator. Its rectangle
    // is the largest axis-aligned one inside the projected outline of the window's cell centres.
    const double east = w.west + (w.columns - 1) * w.step_x, south = w.north - (w.rows - 1) * w.step_y;
    out.lon0 = 0.5 * (w.west + east), out.lat0 = 0.5 * (w.north + south);
    std::vector<Vec2> west_edge, east_edge, south_edge, north_edge;
    for (std::size_t r = 0; r < w.rows; ++r) {
      west_edge.push_back({w.west, w.north - r * w.step_y});
      east_edge.push_back({east, w.north - r * w.step_y});
    }
    for (std::size_t c = 0; c < w.columns; ++c) {
      south_edge.push_back({w.west + c * w.step_x, south});
      north_edge.push_back({w.west + c * w.step_x, w.north});
    }
    for (auto* edge : {&west_edge, &east_edge, &south_edge, &north_edge}) project_to_local_metres(crs, out.lon0, out.lat0, *edge, path);
    double x0 = -HUGE_VAL, x1 = HUGE_VAL, y0 = -HUGE_VAL, y1 = HUGE_VAL;
    for (const Vec2& p : west_edge) x0 = std::max(x0, p.x);
    for (const Vec2& p : east_edge) x1 = std::min(x1, p.x);
    for (const Vec2& p : south_edge) y0 = std::max(y0, p.y);
    for (const Vec2& p : north_edge) y1 = std::min(y1, p.y);
    if (!(x1 > x0 && y1 > y0)) throw InputError(path, "window", "too small to hold a grid once projected");
    t.dx = (x1 - x0) / (t.nx - 1), t.dy = (y1 - y0) / (t.ny - 1);
    t.corner = {x0, y0};
    std::vector<Vec2> where(t.vertex_count());
    for (std::uint32_t j = 0; j < t.ny; ++j)
      for (std::uint32_t i = 0; i < t.nx; ++i) where[t.index(i, j)] = {x0 + i * t.dx, y0 + j * t.dy};
    local_metres_to_geographic(crs, out.lon0, out.lat0, where, path);
    for (std::size_t v = 0; v < where.size(); ++v) {
      // Fractional cell position in the window (column east, row south), clamped onto it: the
      // rectangle lies inside, up to the projection's rounding.
      const double fc = std::clamp((where[v].x - w.west) / w.step_x, 0.0, double(w.columns - 1));
      const double fr = std::clamp((w.north - where[v].y) / w.step_y, 0.0, double(w.rows - 1));
      const std::size_t c = std::min(std::size_t(fc), w.columns - 2), r = std::min(std::size_t(fr), w.rows - 2);
      const double u = fc - c, s = fr - r;
      const std::size_t a = r * w.columns + c;
      const double weight[4] = {(1 - u) * (1 - s), u * (1 - s), (1 - u) * s, u * s};
      const std::size_t cell[4] = {a, a + 1, a + w.columns, a + w.columns + 1};
      double z = 0;
      bool hole = false;
      for (int k = 0; k < 4; ++k) {
        z += weight[k] * w.z[cell[k]];
        hole = hole || (weight[k] > 0.0 && !w.valid[cell[k]]);
      }
      t.z[v] = hole ? 0.0 : z;
      if (masking) t.hole[v] = hole ? 1 : 0;
    }
  }
  if (masking) {
    out.holes = std::size_t(std::count(t.hole.begin(), t.hole.end(), std::uint8_t(1)));
  } else {
    out.filled = std::size_t(std::count(was_valid.begin(), was_valid.end(), std::uint8_t(0)));
  }
  std::ostringstream source;
  source << path << " (" << out.summary() << ")";
  t.source = source.str();
  validate(t, path);
  return out;
}

}  // namespace cullcheck::formats
