// Building footprints with heights: GeoJSON (RFC 7946, and the older "crs" member) read into a
// 2.5D scene (geojson_reader.cpp).
//
//  - Features: a FeatureCollection, or one Feature. Polygon geometry makes one building;
//    MultiPolygon one per part (report.parts_split counts the extra ones). Other geometry (null,
//    points, lines, collections) is skipped and counted.
//  - Ids: the buildings are numbered 0, 1, 2, ... in file order (feature, then part). The scene
//    keeps no feature ids: a report names a building by its number.
//  - Rings: the closing vertex, repeated vertices and spikes (a vertex where the outline turns
//    straight back) are removed; a ring left with under 3 vertices, or not simple (edges cross or
//    touch), is skipped and counted, with the feature named in report.notes. Inner rings (holes)
//    are left out and counted: a Building has no holes, so a courtyard is roofed over (it hides
//    what lies beyond it from an eye above it, and nothing from the street).
//  - Height: FootprintOptions (an attribute in metres, or a storey count times a storey height;
//    neither flag given: the attribute "height" in metres). A number or a numeric string; missing,
//    zero, negative or not a number is "no height" (missing_height, or skipped and counted).
//  - CRS (crs_projection.hpp): FootprintOptions::crs, else the file's "crs" member (its
//    properties.name), else WGS84 longitude/latitude as RFC 7946 says. Longitude/latitude is
//    projected to a transverse Mercator at the data's centre; a projected CRS's coordinates are
//    taken as they are (times its unit); "local" takes them as metres. Coordinates that cannot
//    be longitude/latitude (beyond ±180, ±90) in a file that names no CRS are an InputError
//    asking for --crs.
//  - Far-from-origin scenes are rebased (rebase_if_far), so UTM coordinates keep their precision.
// Malformed files (not JSON, not GeoJSON, a coordinate that is not a number), and files whose
// features all fail to become buildings (a wrong height attribute, say), raise InputError naming
// the file, the feature and the field.
#pragma once

#include <string>

#include "core/formats/import_options.hpp"
#include "core/scene.hpp"

namespace cullcheck::formats {

Scene read_geojson(const std::string& path, const FootprintOptions& options = {}, ImportReport* report = nullptr);
// The same from text; `where` names it in errors.
Scene geojson_from_text(const std::string& text, const FootprintOptions& options = {}, ImportReport* report = nullptr,
                        const std::string& where = "GeoJSON");

// One line saying what a footprint import did with every feature (its counts and CRS).
std::string footprint_import_summary(const ImportReport& report);

// CityJSON 1.0 to 2.0 city models (cityjson_reader.cpp), read as footprints with heights:
//  - Vertices through the file's transform (scale, translate). Every Building and BuildingPart
//    with Solid, MultiSurface, CompositeSurface, MultiSolid or CompositeSolid geometry (its
//    highest LoD) becomes a building per ground surface: its GroundSurface faces (semantics), else
//    the faces flat at its lowest point, else the convex hull of its plan (named in the notes).
//    A Building made only of parts is its parts; other objects (TINRelief terrain, roads, ...) are
//    skipped and counted. Ids 0, 1, 2, ... in the order of the objects' ids.
//  - Height: --height-attribute / --storeys-attribute when given (e.g. RelativeRidgeHeight),
//    else the attribute measuredHeight, else the geometry's own extent (its top above its lowest
//    point). Every building stands on z = 0: terrain is not modelled, so a building on a slope
//    keeps its height above its own ground.
//  - CRS: --crs, else metadata.referenceSystem (a compound CRS by its plan part).
// The roof shapes and walls of LoD2 are not kept: a building is its footprint's prism.
Scene read_cityjson(const std::string& path, const FootprintOptions& options = {}, ImportReport* report = nullptr);
Scene cityjson_from_text(const std::string& text, const FootprintOptions& options = {}, ImportReport* report = nullptr,
                         const std::string& where = "CityJSON");
// Whether a .json file's text is CityJSON (it says "type": "CityJSON" within its first 4 KiB).
bool looks_like_cityjson(const std::string& text);

// Whether a .json file's text is GeoJSON rather than cullcheck's scene JSON (it says
// "FeatureCollection" or "Feature" as its type within its first 4 KiB).
bool looks_like_geojson(const std::string& text);

}  // namespace cullcheck::formats
