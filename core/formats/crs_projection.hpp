// Coordinate reference systems of imported footprints, through PROJ (Debian libproj-dev; kept in
// one translation unit, crs_projection.cpp).
//
// cullcheck works in plan metres. A footprint file's CRS is one of:
//  - projected with a linear unit (UTM, a state plane, a national grid): its coordinates are
//    taken as they are, times the unit's size in metres (US survey feet become metres); the
//    projection's own scale error (UTM: at most 0.04 %) is left in, as every GIS does;
//  - geographic (longitude/latitude in degrees, any datum): projected onto a transverse Mercator
//    touching the ellipsoid at the data's centre (scale error under 1e-5 within 30 km of it),
//    axis order taken as GeoJSON's (longitude first) whatever the CRS's own definition says.
// A compound CRS (plan + vertical, e.g. EPSG:7415 RD New + NAP) is read by its plan part, its
// heights taken as metres. Anything else (a vertical CRS alone, a name PROJ does not know) is an
// InputError.
#pragma once

#include <string>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck::formats {

struct CrsKind {
  bool geographic = false;
  double metres_per_unit = 1.0;  // projected: the size of its linear unit
  std::string name;              // PROJ's name of the CRS, for the import report
};

// What `crs` ("EPSG:26919", "urn:ogc:def:crs:EPSG::26919", "OGC:CRS84", a PROJ string...) is.
// `where` names the input for the error.
CrsKind describe_crs(const std::string& crs, const std::string& where);

// Longitude/latitude in degrees of geographic CRS `crs` (longitude first) to metres of the
// transverse Mercator centred at (lon0, lat0), in place. Throws InputError naming `where` when
// a point cannot be projected.
void project_to_local_metres(const std::string& crs, double lon0, double lat0, std::vector<Vec2>& points,
                             const std::string& where);
// The inverse: metres of that transverse Mercator back to longitude/latitude of `crs`.
void local_metres_to_geographic(const std::string& crs, double lon0, double lat0, std::vector<Vec2>& points,
                                const std::string& where);

}  // namespace cullcheck::formats
