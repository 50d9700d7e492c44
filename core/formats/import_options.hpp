// How scene files are imported, and what an import reports (mesh_formats.hpp: glTF and OBJ;
// footprint_formats.hpp: GeoJSON footprints).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace cullcheck::formats {

// glTF: one object per node that has a mesh, or one per glTF mesh (all its instances merged).
enum class IdSource { node, mesh };
// OBJ files have no stated up axis: cullcheck's own exports are z up, most modelling tools' y up.
enum class UpAxis { y, z };

// Footprint files: where a building's height comes from, and the file's CRS.
struct FootprintOptions {
  std::string height_attribute;   // a property holding the height in metres
  std::string storeys_attribute;  // or one holding a storey count, times storey_height
  double storey_height = 3.5;     // metres (osgEarth's Boston sample extrudes 3.5 m a storey)
  // Height given to a feature whose attribute is missing, not a number or not positive; unset:
  // such features are skipped (and counted).
  std::optional<double> missing_height;
  // Overrides the file's "crs" member: a CRS PROJ knows ("EPSG:26919"), or "local" for plan
  // metres taken as they are. Empty: the file's, else GeoJSON's default (WGS84 longitude/latitude).
  std::string crs;
  // CityJSON: keep each Building and BuildingPart as a mesh object (its surfaces of the highest
  // LoD, triangulated) instead of a footprint prism: what the oracle and mesh-aware methods see.
  bool cityjson_meshes = false;
  // CityJSON, with cityjson_meshes (implied): a Building and its BuildingParts (and theirs) make
  // one mesh object, named by the Building, each part's solid kept apart (no shared vertex), so
  // the object is the building (what the slice-wise method slices and culls), not one solid of it.
  bool cityjson_buildings = false;

  bool operator==(const FootprintOptions&) const = default;
};

struct ImportOptions {
  IdSource ids = IdSource::node;
  UpAxis obj_up = UpAxis::z;
  bool detect_prisms = true;  // false: every object stays a MeshObject (given prisms too)
  FootprintOptions footprints{};
};

struct ImportReport {
  std::size_t objects = 0;
  std::size_t prisms_detected = 0;  // meshes found to be vertical prisms (as_vertical_prism)
  std::size_t prisms_given = 0;     // buildings taken from extras footprint/height
  std::size_t meshes_kept = 0;
  std::size_t degenerate_triangles_dropped = 0;
  // Footprint files: every feature is accounted for, as a building or a count of why not.
  std::size_t features = 0;
  std::size_t buildings = 0;              // objects made from footprints (MultiPolygon parts each one)
  std::size_t parts_split = 0;            // buildings beyond the first of a MultiPolygon feature
  std::size_t holes_filled = 0;           // inner rings left out: the building has no holes (courtyards roofed)
  std::size_t rings_repaired = 0;         // rings that lost repeated vertices or spikes and then were valid
  std::size_t skipped_invalid = 0;        // polygons (or parts) still not simple after repair, or degenerate
  std::size_t skipped_no_height = 0;      // features without a usable height (no missing_height given)
  std::size_t heights_defaulted = 0;      // features given missing_height
  std::size_t skipped_not_polygon = 0;    // features whose geometry is null or not (Multi)Polygon
  std::string crs;                        // how the coordinates were taken (CRS name and what was done)
  std::vector<std::string> notes;         // what was skipped and why (line primitives, images, ...)
};

}  // namespace cullcheck::formats
