// Real elevation models (GeoTIFF, ESRI ASCII grid, or any single-band raster GDAL reads) into a
// Terrain (core/terrain.hpp), through GDAL (Debian libgdal-dev; dem_reader.cpp alone).
//
// Each raster cell's value is the height at the cell's centre, and those centres are the
// terrain's vertices. Heights are the band's values times its scale plus its offset, in metres
// (a band whose unit is feet is converted). The CRS decides the plan:
//  - projected with a linear unit (UTM, a national grid): the grid is regular in it already and
//    is kept, times the unit's size in metres, rebased so that the window's centre is the local
//    origin (its world position is returned);
//  - geographic (EPSG:4326 and the like, as SRTM and USGS 3-arc-second grids): the cells are not
//    square in metres and their east-west size shrinks with latitude, so the grid is resampled
//    onto a regular one in metres of the transverse Mercator touching the ellipsoid at the
//    window's centre (through PROJ, crs_projection.hpp): the largest rectangle of that plane
//    inside the window's footprint, with as many vertices as the window has cells, each height
//    interpolated bilinearly between the four surrounding cell centres.
// NoData cells are filled (the default: layer by layer from the nearest cells with data, each
// taking the mean of its neighbours already filled) or masked (kept as holes: every triangle
// touching one is absent). Rotated or sheared rasters are refused.
#pragma once

#include <cstddef>
#include <string>

#include "core/geometry.hpp"
#include "core/terrain.hpp"

namespace cullcheck::formats {

enum class NoData { fill, mask };

struct DemOptions {
  // A window of the raster in its cells: first column and row (row 0 is the raster's top, the
  // north edge) and size; 0 columns or rows: to the raster's edge.
  std::size_t column = 0, row = 0, columns = 0, rows = 0;
  std::size_t step = 1;  // keep every step-th cell both ways (decimation, no averaging)
  NoData nodata = NoData::fill;
  // Overrides the raster's CRS: one PROJ knows, or "local" for plan metres as they are; needed
  // for a raster without one (an .asc without its .prj).
  std::string crs;
};

struct DemImport {
  Terrain terrain;
  Vec2 origin;               // world position of the local origin (projected CRS; 0 when geographic)
  std::string crs_name;      // PROJ's name of the raster's CRS, or "local"
  bool geographic = false;
  double lon0 = 0, lat0 = 0;        // geographic: the transverse Mercator's centre, degrees
  std::size_t raster_columns = 0, raster_rows = 0;  // of the whole raster
  std::size_t nodata_cells = 0;     // in the window, before decimation
  std::size_t holes = 0;            // vertices left as holes (mask), or 0
  std::size_t filled = 0;           // vertices whose height was filled (fill), or 0
  std::string summary() const;      // one line for the report and the CLI
};

// Throws InputError naming the file and what is wrong: unreadable, not a raster, no CRS and no
// override, rotated, a window outside the raster, a step of 0, a window that decimates to fewer
// than 2 x 2 vertices, no cell with data.
DemImport read_dem(const std::string& path, const DemOptions& options = {});

}  // namespace cullcheck::formats
