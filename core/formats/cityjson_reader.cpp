// CityJSON city models into a 2.5D scene (footprint_formats.hpp says what is read and how).
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/formats/crs_projection.hpp"
#include "core/formats/footprint_formats.hpp"
#include "core/formats/footprint_rings.hpp"
#include "core/formats/polygon_triangulation.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

using nlohmann::json;

constexpr double kGroundTolerance = 0.05;  // m: a face this close to the object's lowest point is on the ground

void note_object(ImportReport& report, const std::string& text) { add_note(report, text, "(further objects are counted, not named)"); }

// One surface of a geometry: its rings (outer first) as vertex indices, and its semantic type.
struct Surface {
  std::vector<std::vector<std::size_t>> rings;
  std::string semantic;
};

double lod_of(const json& g) {
  const json lod = g.value("lod", json());
  if (lod.is_number()) return lod.get<double>();
  if (lod.is_string()) {
    try {
      return std::stod(lod.get<std::string>());
    } catch (const std::exception&) {
    }
  }
  return -1.0;
}

// The semantic type of the surface at `path` in semantics.values (nested like the boundaries
// down to the surface level), or "".
std::string semantic_of(const json& geometry, const std::vector<std::size_t>& path) {
  const json sem = geometry.value("semantics", json());
  if (!sem.is_object() || !sem.contains("values") || !sem.contains("surfaces")) return "";
  const json* v = &sem["values"];
  for (std::size_t k : path) {
    if (!v->is_array() || k >= v->size()) return "";
    v = &(*v)[k];
  }
  if (!v->is_number_unsigned()) return "";
  const json& surfaces = sem["surfaces"];
  const std::size_t i = v->get<std::size_t>();
  return i < surfaces.size() && surfaces[i].is_object() ? surfaces[i].value("type", std::string()) : "";
}

// The surfaces of a Solid, MultiSurface, CompositeSurface, MultiSolid or CompositeSolid.
std::vector<Surface> surfaces_of(const json& g, std::size_t vertex_count, const std::string& where, const std::string& field) {
  const std::string type = g.value("type", std::string());
  const int depth = type == "MultiSurface" || type == "CompositeSurface" ? 0 : type == "Solid" ? 1 : 2;  // levels above a surface
  std::vector<Surface> out;
  auto add_surface = [&](const json& surface, const std::vector<std::size_t>& path) {
    if (!surface.is_array() || surface.empty()) throw InputError(where, field, "holds a surface that is not an array of rings");
    Surface s;
    for (const json& ring : surface) {
      if (!ring.is_array()) throw InputError(where, field, "holds a ring that is not an array of vertex indices");
      std::vector<std::size_t> r;
      for (const json& i : ring) {
        if (!i.is_number_unsigned() || i.get<std::size_t>() >= vertex_count)
          throw InputError(where, field, "names a vertex that does not exist");
        r.push_back(i.get<std::size_t>());
      }
      s.rings.push_back(std::move(r));
    }
    s.semantic = semantic_of(g, path);
    out.push_back(std::move(s));
  };
  // find, not operator[]: on a const json, [] of a missing key is undefined (a fuzzer-found
  // use-after-free, fuzz/regressions/fuzz_cityjson/missing_boundaries.json).
  const auto found = g.find("boundaries");
  if (found == g.end() || !found->is_array()) throw InputError(where, field, "has no boundaries array");
  const json& b = *found;
  std::function<void(const json&, int, std::vector<std::size_t>)> walk = [&](const json& node, int level, std::vector<std::size_t> path) {
    if (!node.is_array()) throw InputError(where, field, "has boundaries nested less deeply than a " + type + "'s");
    for (std::size_t k = 0; k < node.size(); ++k) {
      path.push_back(k);
      if (level == 0) add_surface(node[k], path);
      else walk(node[k], level - 1, path);
      path.pop_back();
    }
  };
  walk(b, depth, {});
  return out;
}

std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// The CRS of the file: --crs, else metadata.referenceSystem (1.0's URN or 1.1/2.0's URL), else none.
std::string crs_of(const json& doc, const FootprintOptions& o, std::string& how) {
  if (!o.crs.empty()) {
    how = "--crs";
    return o.crs == "local" ? "" : o.crs;
  }
  const json meta = doc.value("metadata", json());
  std::string ref = meta.is_object() ? meta.value("referenceSystem", std::string()) : "";
  how = "metadata.referenceSystem";
  // https://www.opengis.net/def/crs/EPSG/0/7415 -> EPSG:7415
  if (const std::size_t at = ref.find("/def/crs/"); at != std::string::npos) {
    std::vector<std::string> parts;
    std::stringstream in(ref.substr(at + 9));
    for (std::string part; std::getline(in, part, '/');) parts.push_back(part);
    if (parts.size() == 3) ref = parts[0] + ":" + parts[2];
  }
  if (ref.empty()) how = "none named: coordinates taken as metres";
  return ref;
}

}  // namespace

bool looks_like_cityjson(const std::string& text) {
  const std::string head = text.substr(0, 4096);
  std::size_t at = head.find("\"type\"");
  while (at != std::string::npos) {
    const std::size_t value = head.find_first_not_of(" \t\r\n:", at + 6);
    if (value != std::string::npos && head.compare(value, 10, "\"CityJSON\"") == 0) return true;
    at = head.find("\"type\"", at + 6);
  }
  return false;
}

Scene cityjson_from_text(const std::string& text, const FootprintOptions& options, ImportReport* report_out, const std::string& where) {
  ImportReport report;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(where, "(document)", std::string("is not valid JSON: ") + e.what());
  }
  try {
    if (!doc.is_object() || doc.value("type", std::string()) != "CityJSON") throw InputError(where, "type", "must be \"CityJSON\"");
    const std::string version = doc.value("version", std::string());
    if (version.empty() || !(version[0] >= '1' && version[0] <= '2'))
      throw InputError(where, "version", "'" + version + "' is not a CityJSON version cullcheck reads (1.0 to 2.0)");
    // Vertices through the transform (required from 1.1; 1.0 files may give real coordinates).
    Vec3 scale{1, 1, 1}, translate{0, 0, 0};
    if (doc.contains("transform")) {
      const json& t = doc["transform"];
      for (const char* key : {"scale", "translate"})
        if (!t.is_object() || !t.contains(key) || !t[key].is_array() || t[key].size() != 3 || !t[key][0].is_number() ||
            !t[key][1].is_number() || !t[key][2].is_number())
          throw InputError(where, std::string("transform.") + key, "must be an array of three numbers");
      scale = {t["scale"][0].get<double>(), t["scale"][1].get<double>(), t["scale"][2].get<double>()};
      translate = {t["translate"][0].get<double>(), t["translate"][1].get<double>(), t["translate"][2].get<double>()};
    }
    if (!doc.contains("vertices") || !doc["vertices"].is_array()) throw InputError(where, "vertices", "must be an array of [x, y, z]");
    if (doc["vertices"].size() > kMaxMeshVertices) throw InputError(where, "vertices", "has more than 50,000,000 entries");
    std::vector<Vec3> vertices;
    vertices.reserve(doc["vertices"].size());
    for (std::size_t i = 0; i < doc["vertices"].size(); ++i) {
      const json& v = doc["vertices"][i];
      if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
        throw InputError(where, "vertices[" + std::to_string(i) + "]", "must be three numbers");
      const Vec3 p{v[0].get<double>() * scale.x + translate.x, v[1].get<double>() * scale.y + translate.y,
                   v[2].get<double>() * scale.z + translate.z};
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || std::abs(p.x) > kMaxCoordinate ||
          std::abs(p.y) > kMaxCoordinate || std::abs(p.z) > kMaxCoordinate)
        throw InputError(where, "vertices[" + std::to_string(i) + "]", "lies beyond 1e9 m from the origin, or is not finite");
      vertices.push_back(p);
    }
    if (!doc.contains("CityObjects") || !doc["CityObjects"].is_object())
      throw InputError(where, "CityObjects", "must be an object of city objects");

    // Every Building and BuildingPart with geometry is one or more buildings (one per ground
    // surface); a Building made only of parts is its parts. Object order: by id (json's map order).
    struct Footprint {
      std::string object;
      std::vector<Vec2> ring;
      double height;
    };
    std::vector<Footprint> footprints;
    // With options.cityjson_meshes: each object's surfaces, triangulated, on its own vertices
    // (with cityjson_buildings, each Building's with its parts', on each part's own vertices).
    struct Mesh {
      std::string object;
      std::vector<Vec3> vertices;
      std::vector<std::array<std::uint32_t, 3>> triangles;
    };
    std::vector<Mesh> meshes;
    std::map<std::string, std::size_t> mesh_of;  // building id -> meshes index (cityjson_buildings)
    const bool as_meshes = options.cityjson_meshes || options.cityjson_buildings;
    const json& city_objects = doc["CityObjects"];
    // The Building a part belongs to: its parents followed up (a missing parent or a cycle stops
    // the walk at the last object found).
    auto building_of = [&](const std::string& id) {
      std::string at = id;
      std::set<std::string> seen{id};
      for (;;) {
        const json& o = city_objects[at];
        if (!o.is_object() || !o.contains("parents") || !o["parents"].is_array() || o["parents"].empty() || !o["parents"][0].is_string())
          return at;
        const std::string parent = o["parents"][0].get<std::string>();
        if (!city_objects.contains(parent) || !seen.insert(parent).second) return at;
        at = parent;
      }
    };
    std::size_t made_of_parts = 0, terrain = 0, flat_surfaces = 0, parts_joined = 0;
    for (const auto& [id, object] : doc["CityObjects"].items()) {
      const std::string name = "CityObjects[\"" + id + "\"]";
      ++report.features;
      const std::string type = object.is_object() ? object.value("type", std::string()) : "";
      const json geometries = object.is_object() ? object.value("geometry", json::array()) : json::array();
      if (type != "Building" && type != "BuildingPart") {
        ++report.skipped_not_polygon;
        if (type == "TINRelief") ++terrain;
        else note_object(report, name + ": a " + (type.empty() ? std::string("typeless object") : type) + ", not a building, skipped");
        continue;
      }
      const json* best = nullptr;
      for (const json& g : geometries) {
        const std::string gt = g.is_object() ? g.value("type", std::string()) : "";
        if (gt != "Solid" && gt != "MultiSurface" && gt != "CompositeSurface" && gt != "MultiSolid" && gt != "CompositeSolid") continue;
        if (!best || lod_of(g) > lod_of(*best)) best = &g;
      }
      if (!best) {
        if (object.contains("children") && object["children"].is_array() && !object["children"].empty()) {
          ++made_of_parts;  // its parts stand for it
        } else {
          ++report.skipped_not_polygon;
          note_object(report, name + ": a " + type + " without surface geometry, skipped");
        }
        continue;
      }
      const std::vector<Surface> surfaces = surfaces_of(*best, vertices.size(), where, name + ".geometry");
      if (as_meshes) {
        Mesh part{id, {}, {}};
        Mesh* target = &part;
        if (options.cityjson_buildings) {
          const std::string building = building_of(id);
          const auto [at, fresh] = mesh_of.emplace(building, meshes.size());
          if (fresh) meshes.push_back({building, {}, {}});
          else ++parts_joined;
          target = &meshes[at->second];
        }
        Mesh& m = *target;
        const std::size_t triangles_before = m.triangles.size();
        std::map<std::size_t, std::uint32_t> local;  // file vertex -> this mesh's (this part's own)
        for (const Surface& surface : surfaces) {
          std::vector<Vec3> points;
          std::vector<std::vector<std::size_t>> rings;
          for (const auto& ring : surface.rings) {
            rings.emplace_back();
            for (std::size_t i : ring) rings.back().push_back(points.size()), points.push_back(vertices[i]);
          }
          const std::size_t given = points.size();
          const auto triangles = triangulate_polygon(points, rings);
          if (triangles.empty()) ++flat_surfaces;
          // Points the triangulation added (rings crossing) are the mesh's own; given ones are shared.
          std::vector<std::uint32_t> index(points.size());
          std::size_t k = 0;
          for (const auto& ring : surface.rings)
            for (std::size_t i : ring) {
              const auto [at, fresh] = local.emplace(i, static_cast<std::uint32_t>(m.vertices.size()));
              if (fresh) m.vertices.push_back(vertices[i]);
              index[k++] = at->second;
            }
          for (std::size_t j = given; j < points.size(); ++j) index[j] = static_cast<std::uint32_t>(m.vertices.size()), m.vertices.push_back(points[j]);
          for (const auto& t : triangles) m.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
        }
        if (m.triangles.size() == triangles_before) {
          ++report.skipped_invalid;
          note_object(report, name + ": no surface spans any area, skipped");
          continue;
        }
        if (target == &part) meshes.push_back(std::move(part));
        continue;
      }
      double z0 = HUGE_VAL, z1 = -HUGE_VAL;
      std::vector<Vec2> plan_points;
      for (const Surface& s : surfaces)
        for (const auto& ring : s.rings)
          for (std::size_t i : ring) z0 = std::min(z0, vertices[i].z), z1 = std::max(z1, vertices[i].z), plan_points.push_back(plan(vertices[i]));
      std::optional<double> height = attribute_height(object.value("attributes", json()), options, "measuredHeight");
      if (!height && (!options.height_attribute.empty() || !options.storeys_attribute.empty()) && options.missing_height) {
        height = options.missing_height;
        ++report.heights_defaulted;
      }
      if (!height && options.height_attribute.empty() && options.storeys_attribute.empty() && z1 > z0) height = z1 - z0;
      if (!height) {
        ++report.skipped_no_height;
        note_object(report, name + ": no usable height, skipped");
        continue;
      }
      // Its footprints: the GroundSurfaces, else the faces lying flat at its lowest point, else
      // the convex hull of its plan (counted: a hull covers more than the building).
      std::vector<std::vector<Vec2>> grounds;
      std::size_t holes = 0;
      auto ring_plan = [&](const std::vector<std::size_t>& ring) {
        std::vector<Vec2> r;
        for (std::size_t i : ring) r.push_back(plan(vertices[i]));
        return r;
      };
      for (const Surface& s : surfaces)
        if (s.semantic == "GroundSurface") grounds.push_back(ring_plan(s.rings[0])), holes += s.rings.size() - 1;
      if (grounds.empty())
        for (const Surface& s : surfaces) {
          bool flat = !s.rings[0].empty();
          for (std::size_t i : s.rings[0]) flat = flat && vertices[i].z <= z0 + kGroundTolerance;
          if (flat) grounds.push_back(ring_plan(s.rings[0])), holes += s.rings.size() - 1;
        }
      if (grounds.empty()) {
        grounds.push_back(convex_hull(plan_points));
        note_object(report, name + ": no ground surface, footprint from the convex hull of its plan");
      }
      report.holes_filled += holes;
      for (std::size_t k = 0; k < grounds.size(); ++k) {
        if (k > 0) ++report.parts_split;
        footprints.push_back({name + (k ? " ground " + std::to_string(k) : ""), std::move(grounds[k]), *height});
      }
    }
    if (terrain > 0)
      note_object(report, std::to_string(terrain) + " TINRelief (terrain) left out: " +
                       (as_meshes ? "each mesh object is lowered to stand on z = 0"
                                                : "buildings stand on z = 0, heights above their own ground"));
    if (flat_surfaces > 0) note_object(report, std::to_string(flat_surfaces) + " surfaces span no area: left out of their meshes");
    if (made_of_parts > 0 && !options.cityjson_buildings)
      note_object(report, std::to_string(made_of_parts) + " Buildings made of BuildingParts: each part a building");
    if (parts_joined > 0) note_object(report, std::to_string(parts_joined) + " BuildingParts joined to their Building's mesh");
    // A building whose every part was skipped leaves an empty mesh.
    std::erase_if(meshes, [](const Mesh& m) { return m.triangles.empty(); });

    // The CRS: a projected plan CRS is taken as it is (times its unit); longitude/latitude is
    // projected to local metres.
    std::string how;
    const std::string crs = crs_of(doc, options, how);
    if (crs.empty()) {
      report.crs = "local metres (" + how + ")";
    } else {
      const CrsKind kind = describe_crs(crs, where);
      if (kind.geographic) {
        Box2 box;
        for (const Footprint& f : footprints)
          for (Vec2 v : f.ring) box.extend(v);
        for (const Mesh& m : meshes)
          for (Vec3 v : m.vertices) box.extend(plan(v));
        const Vec2 c = box.center();
        for (Footprint& f : footprints) project_to_local_metres(crs, c.x, c.y, f.ring, where + ": " + f.object);
        for (Mesh& m : meshes) {
          std::vector<Vec2> points;
          for (Vec3 v : m.vertices) points.push_back(plan(v));
          project_to_local_metres(crs, c.x, c.y, points, where + ": " + m.object);
          for (std::size_t i = 0; i < points.size(); ++i) m.vertices[i].x = points[i].x, m.vertices[i].y = points[i].y;
        }
        report.crs = kind.name + " (" + how + "): longitude/latitude projected to a transverse Mercator at the data's centre";
      } else {
        for (Footprint& f : footprints)
          for (Vec2& v : f.ring) v = v * kind.metres_per_unit;
        for (Mesh& m : meshes)
          for (Vec3& v : m.vertices) v.x *= kind.metres_per_unit, v.y *= kind.metres_per_unit;
        report.crs = kind.name + " (" + how + "): projected, taken as they are";
      }
    }

    Scene scene;
    for (Footprint& f : footprints) {
      bool changed = false;
      std::vector<Vec2> ring = cleaned_ring(std::move(f.ring), changed);
      if (ring.size() >= 3 && signed_area(ring) < 0.0) std::reverse(ring.begin(), ring.end());  // ground faces look down
      std::string why = footprint_problem(ring);
      if (why.empty() && f.height > kMaxHeight) why = "a height beyond 1e4 m";
      if (!why.empty()) {
        ++report.skipped_invalid;
        note_object(report, f.object + ": footprint " + why + (changed ? " after repair" : "") + ", skipped");
        continue;
      }
      if (changed) ++report.rings_repaired;
      Building b;
      b.id = static_cast<ObjectId>(scene.buildings.size());
      b.footprint = std::move(ring);
      b.height = f.height;
      try {
        validate_and_finish(b);
      } catch (const InputError& e) {
        throw e.located(where + ": " + f.object);
      }
      scene.buildings.push_back(std::move(b));
    }
    for (Mesh& m : meshes) {  // each stands on z = 0, as footprint buildings do
      double z0 = HUGE_VAL;
      for (Vec3 v : m.vertices) z0 = std::min(z0, v.z);
      for (Vec3& v : m.vertices) v.z -= z0;
      MeshObject o;
      o.id = static_cast<ObjectId>(scene.meshes.size());
      o.name = std::move(m.object);
      o.vertices = std::move(m.vertices);
      o.triangles = std::move(m.triangles);
      finish_mesh(o);
      scene.meshes.push_back(std::move(o));
    }
    if (report.features > 0 && scene.object_count() == 0)
      throw InputError(where, "CityObjects", "none of the " + std::to_string(report.features) +
                                                 " city objects became a building (" + std::to_string(report.skipped_no_height) +
                                                 " without a usable height, " + std::to_string(report.skipped_invalid) +
                                                 " invalid, " + std::to_string(report.skipped_not_polygon) + " not buildings)");
    rebase_if_far(scene);
    report.buildings = scene.buildings.size();
    report.meshes_kept = scene.meshes.size();
    report.objects = scene.object_count();
    if (report_out) *report_out = std::move(report);
    return scene;
  } catch (const json::exception& e) {
    throw InputError(where, "(document)", std::string("is not CityJSON cullcheck can read: ") + e.what());
  }
}

Scene read_cityjson(const std::string& path, const FootprintOptions& options, ImportReport* report) {
  const std::string text = read_text_file(path);
  if (text.size() > kMaxSceneFileBytes) throw InputError("file " + path, "(size)", "is over 4 GiB");
  return cityjson_from_text(text, options, report, "file " + path);
}

}  // namespace cullcheck::formats
