// GeoJSON footprints into a 2.5D scene (footprint_formats.hpp says what is read and how).
#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/formats/crs_projection.hpp"
#include "core/formats/footprint_formats.hpp"
#include "core/formats/footprint_rings.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

using nlohmann::json;

// One polygon (or MultiPolygon part) waiting for its CRS: its outer ring in file units.
struct Part {
  std::size_t feature;
  std::size_t part;  // index within a MultiPolygon, 0 for a Polygon
  std::vector<Vec2> outer;
  double height;
};

std::string feature_name(std::size_t i) { return "features[" + std::to_string(i) + "]"; }

void note_feature(ImportReport& report, const std::string& text) {
  add_note(report, text, "(further skipped features are counted, not named)");
}

// A linear ring: an array of positions, each an array of at least two numbers.
std::vector<Vec2> ring_of(const json& ring, const std::string& where, const std::string& field) {
  if (!ring.is_array()) throw InputError(where, field, "must be an array of positions");
  std::vector<Vec2> out;
  out.reserve(ring.size());
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const json& p = ring[k];
    if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
      throw InputError(where, field + "[" + std::to_string(k) + "]", "must be a position: an array of two or three numbers");
    out.push_back({p[0].get<double>(), p[1].get<double>()});
  }
  return out;
}

// A Polygon's coordinates: the outer ring, and how many inner rings (holes) it had.
std::vector<Vec2> outer_ring(const json& polygon, const std::string& where, const std::string& field, std::size_t& holes) {
  if (!polygon.is_array() || polygon.empty()) throw InputError(where, field, "must be an array of linear rings (outer ring first)");
  for (std::size_t r = 1; r < polygon.size(); ++r) ring_of(polygon[r], where, field + "[" + std::to_string(r) + "]");
  holes = polygon.size() - 1;
  return ring_of(polygon[0], where, field + "[0]");
}

// The CRS the coordinates are in, by FootprintOptions::crs, the file's "crs" member or RFC 7946.
// Empty for "local"; `how` says where it came from.
std::string crs_of(const json& doc, const FootprintOptions& o, const std::string& where, std::string& how) {
  if (!o.crs.empty()) {
    how = "given by --crs";
    return o.crs == "local" ? "" : o.crs;
  }
  const auto member = doc.find("crs");
  if (member == doc.end() || member->is_null()) {
    how = "GeoJSON's default (the file names no crs)";
    return "OGC:CRS84";
  }
  how = "the file's crs member";
  const json& props = member->is_object() ? member->value("properties", json()) : json();
  if (props.is_object()) {
    const auto name = props.find("name");
    if (name != props.end() && name->is_string()) return name->get<std::string>();
    const auto code = props.find("code");  // the 2008 specification's {"type": "EPSG", "properties": {"code": N}}
    if (code != props.end() && code->is_number_integer()) return "EPSG:" + std::to_string(code->get<long long>());
  }
  throw InputError(where, "crs", "names no CRS (expected {\"type\": \"name\", \"properties\": {\"name\": \"EPSG:...\"}}); pass --crs");
}

}  // namespace

std::string footprint_import_summary(const ImportReport& r) {
  std::ostringstream s;
  s << r.features << " features: " << r.buildings << " buildings (" << r.parts_split << " split off as further parts (MultiPolygon parts, extra ground surfaces), "
    << r.heights_defaulted << " given --missing-height, " << r.rings_repaired << " rings repaired, " << r.holes_filled
    << " holes filled); skipped: " << r.skipped_invalid << " invalid, " << r.skipped_no_height << " without a height, "
    << r.skipped_not_polygon << " not polygons; CRS: " << r.crs;
  return s.str();
}

bool looks_like_geojson(const std::string& text) {
  const std::string head = text.substr(0, 4096);
  return head.find("\"FeatureCollection\"") != std::string::npos || head.find("\"Feature\"") != std::string::npos;
}

Scene geojson_from_text(const std::string& text, const FootprintOptions& options, ImportReport* report_out,
                        const std::string& where) {
  if (!options.height_attribute.empty() && !options.storeys_attribute.empty())
    throw InputError("command line", "--height-attribute", "and --storeys-attribute exclude each other");
  if (!(options.storey_height > 0.0) || !std::isfinite(options.storey_height))
    throw InputError("command line", "--storey-height", "must be a positive number of metres");
  if (options.missing_height && !(*options.missing_height > 0.0 && *options.missing_height <= kMaxHeight))
    throw InputError("command line", "--missing-height", "must be a height in metres, > 0 and at most 1e4");
  ImportReport report;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(where, "(document)", std::string("is not valid JSON: ") + e.what());
  }
  try {
    if (!doc.is_object() || !doc.contains("type") || !doc["type"].is_string())
      throw InputError(where, "type", "must be \"FeatureCollection\" or \"Feature\" (this is not GeoJSON)");
    const std::string type = doc["type"].get<std::string>();
    std::vector<const json*> features;
    if (type == "FeatureCollection") {
      if (!doc.contains("features") || !doc["features"].is_array()) throw InputError(where, "features", "must be an array of Features");
      for (const json& f : doc["features"]) features.push_back(&f);
    } else if (type == "Feature") {
      features.push_back(&doc);
    } else {
      throw InputError(where, "type", "is \"" + type + "\"; cullcheck reads a FeatureCollection or a Feature of footprints");
    }
    if (features.size() > kMaxNodes) throw InputError(where, "features", "has more than 50,000,000 entries");

    std::vector<Part> parts;
    for (std::size_t i = 0; i < features.size(); ++i) {
      const json& f = *features[i];
      const std::string name = feature_name(i);
      ++report.features;
      if (!f.is_object() || f.value("type", json()) != "Feature") throw InputError(where, name + ".type", "must be \"Feature\"");
      const json geometry = f.value("geometry", json());
      const std::string gtype = geometry.is_object() && geometry.contains("type") && geometry["type"].is_string()
                                    ? geometry["type"].get<std::string>()
                                    : "";
      if (gtype != "Polygon" && gtype != "MultiPolygon") {
        ++report.skipped_not_polygon;
        note_feature(report, name + ": geometry " + (gtype.empty() ? "null" : gtype) + " is no footprint, skipped");
        continue;
      }
      if (!geometry.contains("coordinates")) throw InputError(where, name + ".geometry.coordinates", "is missing");
      const json& coords = geometry["coordinates"];
      std::vector<std::vector<Vec2>> outers;
      std::size_t holes = 0;
      if (gtype == "Polygon") {
        outers.push_back(outer_ring(coords, where, name + ".geometry.coordinates", holes));
      } else {
        if (!coords.is_array()) throw InputError(where, name + ".geometry.coordinates", "must be an array of polygons");
        for (std::size_t p = 0; p < coords.size(); ++p) {
          std::size_t h = 0;
          outers.push_back(outer_ring(coords[p], where, name + ".geometry.coordinates[" + std::to_string(p) + "]", h));
          holes += h;
        }
        if (outers.empty()) {
          ++report.skipped_invalid;
          note_feature(report, name + ": an empty MultiPolygon, skipped");
          continue;
        }
      }
      std::optional<double> height = attribute_height(f.value("properties", json()), options, "height");
      if (!height) {
        if (!options.missing_height) {
          ++report.skipped_no_height;
          note_feature(report, name + ": no usable height, skipped (--missing-height gives one)");
          continue;
        }
        height = options.missing_height;
        ++report.heights_defaulted;
      }
      if (*height > kMaxHeight) {
        ++report.skipped_invalid;
        note_feature(report, name + ": height " + std::to_string(*height) + " m is beyond 1e4 m, skipped");
        continue;
      }
      report.holes_filled += holes;
      for (std::size_t p = 0; p < outers.size(); ++p) parts.push_back({i, p, std::move(outers[p]), *height});
    }

    // The CRS, and every outer ring in plan metres.
    std::string how;
    const std::string crs = crs_of(doc, options, where, how);
    if (crs.empty()) {
      report.crs = "local metres (" + how + "): coordinates taken as they are";
    } else {
      const CrsKind kind = describe_crs(crs, where);
      if (kind.geographic) {
        double lo_x = HUGE_VAL, hi_x = -HUGE_VAL, lo_y = HUGE_VAL, hi_y = -HUGE_VAL;
        for (const Part& part : parts)
          for (Vec2 v : part.outer) lo_x = std::min(lo_x, v.x), hi_x = std::max(hi_x, v.x), lo_y = std::min(lo_y, v.y), hi_y = std::max(hi_y, v.y);
        if (!parts.empty()) {
          if (!(lo_x >= -180.0 && hi_x <= 180.0 && lo_y >= -90.0 && hi_y <= 90.0))
            throw InputError(where, "crs", kind.name + " (" + how + ") is longitude/latitude, but the coordinates reach (" +
                                               std::to_string(lo_x) + ", " + std::to_string(lo_y) + ") - (" + std::to_string(hi_x) +
                                               ", " + std::to_string(hi_y) + "): name the file's CRS with --crs (e.g. EPSG:26919, or local)");
          const double lon0 = (lo_x + hi_x) / 2, lat0 = (lo_y + hi_y) / 2;
          for (Part& part : parts) project_to_local_metres(crs, lon0, lat0, part.outer, where + ": " + feature_name(part.feature));
          std::ostringstream text;
          text.precision(9);
          text << kind.name << " (" << how << "): longitude/latitude projected to a transverse Mercator at (" << lon0 << ", "
               << lat0 << ")";
          report.crs = text.str();
        } else {
          report.crs = kind.name + " (" + how + "): longitude/latitude (no footprints to project)";
        }
      } else {
        for (Part& part : parts)
          for (Vec2& v : part.outer) v = v * kind.metres_per_unit;
        std::ostringstream text;
        text.precision(12);
        text << kind.name << " (" << how << "): projected, taken as they are";
        if (kind.metres_per_unit != 1.0) text << " times " << kind.metres_per_unit << " m a unit";
        report.crs = text.str();
      }
    }

    Scene scene;
    for (Part& part : parts) {
      const std::string name = feature_name(part.feature) + (part.part ? " part " + std::to_string(part.part) : "");
      bool changed = false;
      std::vector<Vec2> ring = cleaned_ring(std::move(part.outer), changed);
      for (Vec2 v : ring)
        if (!(std::abs(v.x) <= kMaxCoordinate && std::abs(v.y) <= kMaxCoordinate))
          throw InputError(where, feature_name(part.feature) + ".geometry.coordinates", "lies beyond 1e9 m from the origin");
      std::string why = footprint_problem(ring);
      if (!why.empty()) {
        ++report.skipped_invalid;
        note_feature(report, name + ": footprint " + why + (changed ? " after repair" : "") + ", skipped");
        continue;
      }
      if (changed) ++report.rings_repaired;
      if (part.part > 0) ++report.parts_split;
      Building b;
      b.id = static_cast<ObjectId>(scene.buildings.size());
      b.footprint = std::move(ring);
      b.height = part.height;
      try {
        validate_and_finish(b);
      } catch (const InputError& e) {
        throw e.located(where + ": " + name);
      }
      scene.buildings.push_back(std::move(b));
    }
    // Features but no building is a reading mistake (a wrong attribute name, say), not a city.
    if (report.features > 0 && scene.buildings.empty())
      throw InputError(where, "features", "none of the " + std::to_string(report.features) + " features became a building (" +
                                              std::to_string(report.skipped_no_height) + " without a usable height: name it with " +
                                              "--height-attribute, --storeys-attribute or --missing-height; " +
                                              std::to_string(report.skipped_invalid) + " invalid; " +
                                              std::to_string(report.skipped_not_polygon) + " not polygons)");
    rebase_if_far(scene);
    report.objects = report.buildings = scene.buildings.size();
    if (report_out) *report_out = std::move(report);
    return scene;
  } catch (const json::exception& e) {  // a value of an unexpected type the checks above let through
    throw InputError(where, "(document)", std::string("is not GeoJSON cullcheck can read: ") + e.what());
  }
}

Scene read_geojson(const std::string& path, const FootprintOptions& options, ImportReport* report) {
  const std::string text = read_text_file(path);
  if (text.size() > kMaxSceneFileBytes) throw InputError("file " + path, "(size)", "is over 4 GiB");
  return geojson_from_text(text, options, report, "file " + path);
}

}  // namespace cullcheck::formats
