#include "core/scene_io.hpp"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/errors.hpp"

namespace cullcheck {
namespace {

using nlohmann::json;

std::string building_name(std::size_t index, const json& j) {
  if (j.is_object() && j.contains("id") && j["id"].is_number_integer())
    return "building " + std::to_string(j["id"].get<long long>());
  return "building at index " + std::to_string(index);
}

double finite_number(const json& j, const std::string& object, const std::string& field) {
  if (!j.is_number()) throw InputError(object, field, "must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw InputError(object, field, "must be finite (got " + j.dump() + ")");
  return v;
}

const json& member(const json& j, const char* key, const std::string& object) {
  if (!j.is_object()) throw InputError(object, key, "enclosing value is not a JSON object");
  auto it = j.find(key);
  if (it == j.end()) throw InputError(object, key, "is missing");
  return *it;
}

json parse(const std::string& text, const std::string& what) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers that overflow a double
    throw InputError(what, "(document)", std::string("is not valid JSON: ") + e.what());
  }
}

// Shortest round-trip text for a double, so writing is deterministic and lossless.
json number(double v) { return v == 0.0 ? json(0.0) : json(v); }

}  // namespace

void validate_and_finish(Building& b) {
  const std::string object = "building " + std::to_string(b.id);
  if (!std::isfinite(b.height) || b.height <= 0.0)
    throw InputError(object, "height", "must be finite and > 0 (got " + std::to_string(b.height) + ")");
  if (b.height > kMaxHeight) throw InputError(object, "height", "exceeds the limit of 1e4 m");
  auto& ring = b.footprint;
  if (ring.size() >= 2 && ring.front() == ring.back()) ring.pop_back();  // explicit closing vertex
  if (ring.size() < 3) throw InputError(object, "footprint", "needs at least 3 distinct vertices");
  if (ring.size() > kMaxFootprintVertices) throw InputError(object, "footprint", "has more than 4096 vertices");
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (!std::isfinite(ring[i].x) || !std::isfinite(ring[i].y))
      throw InputError(object, "footprint[" + std::to_string(i) + "]", "must be finite");
    if (std::abs(ring[i].x) > kMaxCoordinate || std::abs(ring[i].y) > kMaxCoordinate)
      throw InputError(object, "footprint[" + std::to_string(i) + "]", "lies beyond 1e9 m from the origin");
    if (ring[i] == ring[(i + 1) % ring.size()])
      throw InputError(object, "footprint[" + std::to_string(i) + "]", "repeats the next vertex");
  }
  if (!is_simple(ring)) throw InputError(object, "footprint", "is not a simple polygon (edges cross or touch)");
  const double area = signed_area(ring);
  if (area == 0.0 || !std::isfinite(area)) throw InputError(object, "footprint", "has zero area");
  if (area < 0.0) std::reverse(ring.begin(), ring.end());
  finish_building(b);
}

std::size_t validate_and_finish(MeshObject& m, bool drop_degenerate) {
  const std::string object = "mesh " + std::to_string(m.id);
  if (m.vertices.size() > kMaxMeshVertices) throw InputError(object, "vertices", "has more than 50,000,000 entries");
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3 v = m.vertices[i];
    const std::string field = "vertices[" + std::to_string(i) + "]";
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) throw InputError(object, field, "must be finite");
    if (std::abs(v.x) > kMaxCoordinate || std::abs(v.y) > kMaxCoordinate)
      throw InputError(object, field, "lies beyond 1e9 m from the origin");
    if (std::abs(v.z) > kMaxHeight) throw InputError(object, field, "lies beyond 1e4 m above or below the ground");
  }
  std::size_t dropped = 0;
  std::vector<std::array<std::uint32_t, 3>> kept;
  kept.reserve(m.triangles.size());
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& t = m.triangles[i];
    const std::string field = "triangles[" + std::to_string(i) + "]";
    for (std::uint32_t k : t)
      if (k >= m.vertices.size())
        throw InputError(object, field, "index " + std::to_string(k) + " is out of range (" + std::to_string(m.vertices.size()) + " vertices)");
    const Vec3 n = cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
    if (!(dot(n, n) > 0.0)) {
      if (!drop_degenerate) throw InputError(object, field, "has zero area");
      ++dropped;
      continue;
    }
    kept.push_back(t);
  }
  m.triangles = std::move(kept);
  if (m.triangles.empty()) throw InputError(object, "triangles", "holds no triangle of positive area");
  finish_mesh(m);
  return dropped;
}

Building box_building(ObjectId id, double x0, double y0, double x1, double y1, double height) {
  Building b;
  b.id = id;
  b.height = height;
  b.footprint = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  validate_and_finish(b);
  return b;
}

Building footprint_building(ObjectId id, std::vector<Vec2> footprint, double height) {
  Building b;
  b.id = id;
  b.footprint = std::move(footprint);
  b.height = height;
  validate_and_finish(b);
  return b;
}

void rebase_if_far(Scene& scene) {
  if (scene.object_count() == 0) return;
  const Box2 box = scene.bounds().plan();
  const double nearest = std::max({0.0, std::min(std::abs(box.lo.x), std::abs(box.hi.x)),
                                   std::min(std::abs(box.lo.y), std::abs(box.hi.y))});
  if (nearest < kRebaseThreshold) return;
  // A whole-metre origin near the centre: subtracting it is exact for coordinates within a
  // factor of two of it (Sterbenz), so writing the scene back reproduces the input.
  const Vec2 shift{std::round(box.center().x), std::round(box.center().y)};
  for (Building& b : scene.buildings) {
    for (Vec2& p : b.footprint) p = p - shift;
    finish_building(b);
  }
  for (MeshObject& m : scene.meshes) {
    for (Vec3& v : m.vertices) v = v - Vec3{shift.x, shift.y, 0.0};
    finish_mesh(m);
  }
  scene.origin = scene.origin + shift;
}

Scene scene_from_json_text(const std::string& text) {
  const json doc = parse(text, "scene");
  if (!doc.is_object()) throw InputError("scene", "(document)", "must be a JSON object");
  const json& format = member(doc, "format", "scene");
  if (format != "cullcheck-scene") throw InputError("scene", "format", "must be \"cullcheck-scene\"");
  const json& version = member(doc, "version", "scene");
  if (version != 1 && version != 2)
    throw InputError("scene", "version", "unsupported version " + version.dump() + " (expected 1, or 2 with meshes)");
  Scene scene;
  if (auto it = doc.find("provenance"); it != doc.end()) {
    if (!it->is_object()) throw InputError("scene", "provenance", "must be an object");
    if (auto g = it->find("generator"); g != it->end() && g->is_string()) scene.provenance.generator = *g;
    if (auto s = it->find("seed"); s != it->end()) {
      if (!s->is_number_unsigned()) throw InputError("scene", "provenance.seed", "must be a non-negative integer");
      scene.provenance.seed = s->get<std::uint64_t>();
    }
    if (auto p = it->find("parameters"); p != it->end()) scene.provenance.parameters_json = p->dump();
  }
  if (auto it = doc.find("origin"); it != doc.end()) {
    if (!it->is_array() || it->size() != 2) throw InputError("scene", "origin", "must be [x, y]");
    scene.origin = {finite_number((*it)[0], "scene", "origin[0]"), finite_number((*it)[1], "scene", "origin[1]")};
  }
  const json& buildings = member(doc, "buildings", "scene");
  if (!buildings.is_array()) throw InputError("scene", "buildings", "must be an array");
  if (buildings.size() > kMaxBuildings) throw InputError("scene", "buildings", "has more than 20,000,000 entries");
  if (auto it = doc.find("building_count"); it != doc.end() && *it != buildings.size())
    throw InputError("scene", "building_count", "says " + it->dump() + " but the file holds " + std::to_string(buildings.size()));
  scene.buildings.reserve(buildings.size());
  std::set<ObjectId> ids;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    const json& jb = buildings[i];
    const std::string object = building_name(i, jb);
    Building b;
    const json& id = member(jb, "id", object);
    if (!id.is_number_integer() || id.get<long long>() < 0 || id.get<long long>() > 0xFFFFFFFFLL)
      throw InputError(object, "id", "must be an integer in [0, 2^32)");
    b.id = static_cast<ObjectId>(id.get<long long>());
    if (!ids.insert(b.id).second) throw InputError(object, "id", "is a duplicate");
    b.height = finite_number(member(jb, "height", object), object, "height");
    const json& fp = member(jb, "footprint", object);
    if (!fp.is_array()) throw InputError(object, "footprint", "must be an array of [x, y] pairs");
    if (fp.size() > kMaxFootprintVertices + 1) throw InputError(object, "footprint", "has more than 4096 vertices");
    for (std::size_t k = 0; k < fp.size(); ++k) {
      const std::string field = "footprint[" + std::to_string(k) + "]";
      if (!fp[k].is_array() || fp[k].size() != 2) throw InputError(object, field, "must be [x, y]");
      b.footprint.push_back({finite_number(fp[k][0], object, field + "[0]"), finite_number(fp[k][1], object, field + "[1]")});
    }
    validate_and_finish(b);
    scene.buildings.push_back(std::move(b));
  }
  if (auto it = doc.find("meshes"); it != doc.end()) {
    if (version == 1) throw InputError("scene", "meshes", "needs format version 2");
    if (!it->is_array()) throw InputError("scene", "meshes", "must be an array");
    if (it->size() > kMaxMeshes) throw InputError("scene", "meshes", "has more than 20,000,000 entries");
    for (std::size_t i = 0; i < it->size(); ++i) {
      const json& jm = (*it)[i];
      std::string object = "mesh at index " + std::to_string(i);
      if (jm.is_object() && jm.contains("id") && jm["id"].is_number_integer())
        object = "mesh " + std::to_string(jm["id"].get<long long>());
      MeshObject m;
      const json& id = member(jm, "id", object);
      if (!id.is_number_integer() || id.get<long long>() < 0 || id.get<long long>() > 0xFFFFFFFFLL)
        throw InputError(object, "id", "must be an integer in [0, 2^32)");
      m.id = static_cast<ObjectId>(id.get<long long>());
      if (!ids.insert(m.id).second) throw InputError(object, "id", "is a duplicate (ids are unique across buildings and meshes)");
      if (auto n = jm.find("name"); n != jm.end()) {
        if (!n->is_string()) throw InputError(object, "name", "must be a string");
        m.name = *n;
      }
      const json& vs = member(jm, "vertices", object);
      if (!vs.is_array()) throw InputError(object, "vertices", "must be an array of [x, y, z] triples");
      if (vs.size() > kMaxMeshVertices) throw InputError(object, "vertices", "has more than 50,000,000 entries");
      m.vertices.reserve(vs.size());
      for (std::size_t k = 0; k < vs.size(); ++k) {
        const std::string field = "vertices[" + std::to_string(k) + "]";
        if (!vs[k].is_array() || vs[k].size() != 3) throw InputError(object, field, "must be [x, y, z]");
        m.vertices.push_back({finite_number(vs[k][0], object, field + "[0]"), finite_number(vs[k][1], object, field + "[1]"),
                              finite_number(vs[k][2], object, field + "[2]")});
      }
      const json& ts = member(jm, "triangles", object);
      if (!ts.is_array()) throw InputError(object, "triangles", "must be an array of [i, j, k] index triples");
      m.triangles.reserve(ts.size());
      for (std::size_t k = 0; k < ts.size(); ++k) {
        const std::string field = "triangles[" + std::to_string(k) + "]";
        if (!ts[k].is_array() || ts[k].size() != 3) throw InputError(object, field, "must be [i, j, k]");
        std::array<std::uint32_t, 3> t{};
        for (int c = 0; c < 3; ++c) {
          if (!ts[k][c].is_number_unsigned() || ts[k][c].get<std::uint64_t>() > 0xFFFFFFFFULL)
            throw InputError(object, field, "indices must be integers in [0, 2^32)");
          t[c] = static_cast<std::uint32_t>(ts[k][c].get<std::uint64_t>());
        }
        m.triangles.push_back(t);
      }
      validate_and_finish(m);
      scene.meshes.push_back(std::move(m));
    }
  }
  rebase_if_far(scene);
  return scene;
}

std::string scene_to_json_text(const Scene& scene) {
  json doc;
  doc["format"] = "cullcheck-scene";
  doc["version"] = scene.meshes.empty() ? 1 : 2;
  doc["provenance"] = {{"generator", scene.provenance.generator},
                       {"seed", scene.provenance.seed},
                       {"parameters", json::parse(scene.provenance.parameters_json)}};
  doc["building_count"] = scene.buildings.size();
  json buildings = json::array();
  for (const Building& b : scene.buildings) {
    json fp = json::array();
    for (Vec2 p : b.footprint) fp.push_back({number(p.x + scene.origin.x), number(p.y + scene.origin.y)});
    buildings.push_back({{"id", b.id}, {"height", number(b.height)}, {"footprint", std::move(fp)}});
  }
  // Coordinates are written in world space (origin added back), so no "origin" is needed.
  doc["buildings"] = std::move(buildings);
  if (!scene.meshes.empty()) {
    json meshes = json::array();
    for (const MeshObject& m : scene.meshes) {
      json vs = json::array();
      for (Vec3 v : m.vertices) vs.push_back({number(v.x + scene.origin.x), number(v.y + scene.origin.y), number(v.z)});
      json ts = json::array();
      for (const auto& t : m.triangles) ts.push_back({t[0], t[1], t[2]});
      json jm = {{"id", m.id}};
      if (!m.name.empty()) jm["name"] = m.name;
      jm["vertices"] = std::move(vs);
      jm["triangles"] = std::move(ts);
      meshes.push_back(std::move(jm));
    }
    doc["meshes"] = std::move(meshes);
  }
  return doc.dump() + "\n";
}

Scene read_scene_file(const std::string& path) {
  try {
    return scene_from_json_text(read_text_file(path));
  } catch (const InputError& e) {
    throw e.located(path);
  }
}

CameraPath read_path_file(const std::string& path) {
  const std::string text = read_text_file(path);
  try {
    return path_from_json_text(text);
  } catch (const InputError& e) {
    throw e.located(path);
  }
}

void write_scene_file(const Scene& scene, const std::string& path) { write_text_file_atomically(path, scene_to_json_text(scene)); }

namespace {

json camera_json(const Camera& c) {
  json j = {{"position", {number(c.position.x), number(c.position.y), number(c.position.z)}},
            {"yaw", number(c.yaw)},
            {"pitch", number(c.pitch)},
            {"roll", number(c.roll)}};
  if (c.orthographic()) {
    j["projection"] = "orthographic";
    j["ortho_width"] = number(c.ortho_width);
    j["ortho_height"] = number(c.ortho_height);
  } else {
    j["hfov"] = number(c.hfov);
    j["vfov"] = number(c.vfov);
  }
  j["near"] = number(c.near);
  j["far"] = number(c.far);
  if (c.width > 0) j["resolution"] = {c.width, c.height};
  return j;
}

// "coordinates" and "origin" say which frame a camera or path file is in (core/coordinates.hpp).
void read_frame_keys(const json& j, const std::string& object, CameraPath& out) {
  if (auto it = j.find("coordinates"); it != j.end()) {
    if (*it == "local") out.coordinates = CoordinateFrame::local;
    else if (*it == "world") out.coordinates = CoordinateFrame::world;
    else throw InputError(object, "coordinates", "must be \"local\" (scene-local metres) or \"world\" (local + the scene's origin), got " + it->dump());
  }
  if (auto it = j.find("origin"); it != j.end()) {
    if (out.coordinates == CoordinateFrame::world)
      throw InputError(object, "origin", "names the origin local coordinates are relative to: world coordinates have none");
    if (!it->is_array() || it->size() != 2) throw InputError(object, "origin", "must be [x, y]");
    out.origin = Vec2{finite_number((*it)[0], object, "origin[0]"), finite_number((*it)[1], object, "origin[1]")};
    out.coordinates = CoordinateFrame::local;
  }
}

// A frame key where no frame may be declared is an error, not ignored: a camera in world
// coordinates read as local would be kilometres off and see nothing.
void reject_frame_keys(const json& j, const std::string& object, const char* why) {
  for (const char* key : {"coordinates", "origin"})
    if (j.is_object() && j.contains(key)) throw InputError(object, key, why);
}

Camera camera_from(const json& j, const std::string& object) {
  Camera c;
  const json& p = member(j, "position", object);
  if (!p.is_array() || p.size() != 3) throw InputError(object, "position", "must be [x, y, z]");
  c.position = {finite_number(p[0], object, "position[0]"), finite_number(p[1], object, "position[1]"),
                finite_number(p[2], object, "position[2]")};
  auto optional = [&](const char* key, double& field) {
    if (auto it = j.find(key); it == j.end()) return false;
    else field = finite_number(*it, object, key);
    return true;
  };
  optional("yaw", c.yaw), optional("pitch", c.pitch), optional("roll", c.roll);
  optional("near", c.near), optional("far", c.far);
  if (auto it = j.find("projection"); it != j.end()) {
    if (*it == "orthographic") c.projection = Projection::orthographic;
    else if (*it != "perspective") throw InputError(object, "projection", "must be \"perspective\" or \"orthographic\"");
  }
  if (auto it = j.find("resolution"); it != j.end()) {
    if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number_integer() || !(*it)[1].is_number_integer())
      throw InputError(object, "resolution", "must be [width, height] in whole pixels");
    const long long w = (*it)[0], h = (*it)[1];
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
      throw InputError(object, "resolution", "each side must lie in [1, 8192] pixels");
    c.width = static_cast<int>(w), c.height = static_cast<int>(h);
  }
  double aspect = 0.0;
  const bool explicit_aspect = optional("aspect", aspect);
  if (explicit_aspect && !(aspect > 0.0)) throw InputError(object, "aspect", "must be > 0");
  if (!explicit_aspect && c.width > 0) aspect = double(c.width) / double(c.height);
  // The across field, the up field and their ratio: any two give the third.
  const bool ortho = c.orthographic();
  const char* across = ortho ? "ortho_width" : "hfov";
  const char* up = ortho ? "ortho_height" : "vfov";
  if (ortho) c.ortho_width = c.ortho_height = 0.0;
  double& a = ortho ? c.ortho_width : c.hfov;
  double& b = ortho ? c.ortho_height : c.vfov;
  const bool has_a = optional(across, a), has_b = optional(up, b);
  if (has_a && has_b && explicit_aspect)
    throw InputError(object, "aspect", std::string("give two of ") + across + ", " + up + " and aspect, not all three");
  const bool panorama = !ortho && has_a && c.hfov >= kTwoPi;
  if (aspect > 0.0 && !panorama && !(has_a && has_b)) {
    if (ortho) {
      if (!has_a && !has_b) throw InputError(object, "ortho_width", "an orthographic camera needs ortho_width or ortho_height");
      if (has_a) b = a / aspect;
      else a = b * aspect;
    } else if (has_b && !has_a) {
      a = 2.0 * std::atan(std::tan(b / 2) * aspect);
    } else {
      b = 2.0 * std::atan(std::tan(a / 2) / aspect);
    }
  } else if (ortho && !(has_a && has_b)) {
    throw InputError(object, has_a ? up : across, "an orthographic camera needs ortho_width and ortho_height (or one and an aspect)");
  }
  validate(c, object);
  return c;
}

}  // namespace

std::string camera_to_json_text(const Camera& camera) { return camera_json(camera).dump() + "\n"; }

Camera camera_from_json_text(const std::string& text, const std::string& object) {
  const json j = parse(text, object);
  reject_frame_keys(j, object, "cameras here are scene-local: only camera files and flags (--camera, --from) say their frame");
  return camera_from(j, object);
}

CameraPath single_camera_from_json_text(const std::string& text, const std::string& object) {
  json j = parse(text, object);
  CameraPath path;
  path.kind = "single_camera";
  read_frame_keys(j, object, path);
  if (j.is_object()) j.erase("coordinates"), j.erase("origin");
  path.frames.push_back(camera_from(j, object));
  return path;
}

std::string path_to_json_text(const CameraPath& path) {
  json frames = json::array();
  for (const Camera& c : path.frames) frames.push_back(camera_json(c));
  json doc = {{"format", "cullcheck-path"}, {"version", 1},         {"kind", path.kind},
              {"seed", path.seed},          {"frames_per_second", number(path.frames_per_second)},
              {"frames", std::move(frames)}};
  if (path.coordinates) doc["coordinates"] = *path.coordinates == CoordinateFrame::world ? "world" : "local";
  if (path.origin) doc["origin"] = {number(path.origin->x), number(path.origin->y)};
  if (!path.events.empty()) {
    json events = json::array();
    for (const SceneEvent& e : path.events) {
      json event = {{"frame", e.frame}};
      if (!e.appear.empty()) event["appear"] = e.appear;
      if (!e.vanish.empty()) event["vanish"] = e.vanish;
      events.push_back(std::move(event));
    }
    doc["events"] = std::move(events);
  }
  return doc.dump() + "\n";
}

CameraPath path_from_json_text(const std::string& text) {
  const json doc = parse(text, "path");
  if (member(doc, "format", "path") != "cullcheck-path") throw InputError("path", "format", "must be \"cullcheck-path\"");
  CameraPath path;
  if (auto it = doc.find("kind"); it != doc.end() && it->is_string()) path.kind = *it;
  if (auto it = doc.find("seed"); it != doc.end() && it->is_number_unsigned()) path.seed = *it;
  path.frames_per_second = finite_number(member(doc, "frames_per_second", "path"), "path", "frames_per_second");
  if (path.frames_per_second <= 0) throw InputError("path", "frames_per_second", "must be > 0");
  read_frame_keys(doc, "path", path);
  const json& frames = member(doc, "frames", "path");
  if (!frames.is_array()) throw InputError("path", "frames", "must be an array");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string object = "path frame " + std::to_string(i);
    reject_frame_keys(frames[i], object, "belongs to the whole path (its top level), not to one frame");
    path.frames.push_back(camera_from(frames[i], object));
  }
  if (auto it = doc.find("events"); it != doc.end()) {
    if (!it->is_array()) throw InputError("path", "events", "must be an array of {\"frame\": N, \"appear\": [ids], \"vanish\": [ids]}");
    for (std::size_t i = 0; i < it->size(); ++i) {
      const json& e = (*it)[i];
      const std::string object = "path event " + std::to_string(i);
      if (!e.is_object()) throw InputError(object, "(event)", "must be an object");
      for (const auto& [key, value] : e.items())
        if (key != "frame" && key != "appear" && key != "vanish") throw InputError(object, key, "is not a field of an event (frame, appear, vanish)");
      SceneEvent event;
      const json& frame = member(e, "frame", object);
      if (!frame.is_number_unsigned()) throw InputError(object, "frame", "must be a frame number (an integer >= 0)");
      event.frame = frame.get<std::size_t>();
      for (const char* key : {"appear", "vanish"}) {
        auto& ids = std::string(key) == "appear" ? event.appear : event.vanish;
        if (auto list = e.find(key); list != e.end()) {
          if (!list->is_array()) throw InputError(object, key, "must be an array of object ids");
          for (const json& id : *list) {
            if (!id.is_number_unsigned() || id.get<std::uint64_t>() > 0xffffffffu) throw InputError(object, key, "holds " + id.dump() + ", not an object id");
            ids.push_back(id.get<ObjectId>());
          }
          std::sort(ids.begin(), ids.end());
          if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) throw InputError(object, key, "names an object twice");
        }
      }
      path.events.push_back(std::move(event));
    }
  }
  return path;
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("file " + path, "(file)", "cannot be opened for reading");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError("file " + path, "(file)", "cannot be opened for writing");
    out << text;
    out.flush();
    if (!out) throw InputError("file " + path, "(file)", "write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError("file " + path, "(file)", "cannot replace the existing file");
  }
}

}  // namespace cullcheck
