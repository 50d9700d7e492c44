#include "core/scene_io.hpp"

#include <cmath>
#include <cstdio>
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

Building box_building(ObjectId id, double x0, double y0, double x1, double y1, double height) {
  Building b;
  b.id = id;
  b.height = height;
  b.footprint = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  validate_and_finish(b);
  return b;
}

void rebase_if_far(Scene& scene) {
  if (scene.buildings.empty()) return;
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
  scene.origin = scene.origin + shift;
}

Scene scene_from_json_text(const std::string& text) {
  const json doc = parse(text, "scene");
  if (!doc.is_object()) throw InputError("scene", "(document)", "must be a JSON object");
  const json& format = member(doc, "format", "scene");
  if (format != "cullcheck-scene") throw InputError("scene", "format", "must be \"cullcheck-scene\"");
  const json& version = member(doc, "version", "scene");
  if (version != 1) throw InputError("scene", "version", "unsupported version " + version.dump() + " (expected 1)");
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
  rebase_if_far(scene);
  return scene;
}

std::string scene_to_json_text(const Scene& scene) {
  json doc;
  doc["format"] = "cullcheck-scene";
  doc["version"] = 1;
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
  return doc.dump() + "\n";
}

Scene read_scene_file(const std::string& path) {
  try {
    return scene_from_json_text(read_text_file(path));
  } catch (const InputError& e) {
    throw e.located(path);
  }
}

void write_scene_file(const Scene& scene, const std::string& path) { write_text_file_atomically(path, scene_to_json_text(scene)); }

namespace {

json camera_json(const Camera& c) {
  return {{"position", {number(c.position.x), number(c.position.y), number(c.position.z)}},
          {"yaw", number(c.yaw)},   {"pitch", number(c.pitch)}, {"roll", number(c.roll)},
          {"hfov", number(c.hfov)}, {"vfov", number(c.vfov)},   {"near", number(c.near)},
          {"far", number(c.far)}};
}

Camera camera_from(const json& j, const std::string& object) {
  Camera c;
  const json& p = member(j, "position", object);
  if (!p.is_array() || p.size() != 3) throw InputError(object, "position", "must be [x, y, z]");
  c.position = {finite_number(p[0], object, "position[0]"), finite_number(p[1], object, "position[1]"),
                finite_number(p[2], object, "position[2]")};
  auto optional = [&](const char* key, double& field) {
    if (auto it = j.find(key); it != j.end()) field = finite_number(*it, object, key);
  };
  optional("yaw", c.yaw), optional("pitch", c.pitch), optional("roll", c.roll);
  optional("hfov", c.hfov), optional("vfov", c.vfov), optional("near", c.near), optional("far", c.far);
  validate(c, object);
  return c;
}

}  // namespace

std::string camera_to_json_text(const Camera& camera) { return camera_json(camera).dump() + "\n"; }

Camera camera_from_json_text(const std::string& text, const std::string& object) {
  return camera_from(parse(text, object), object);
}

std::string path_to_json_text(const CameraPath& path) {
  json frames = json::array();
  for (const Camera& c : path.frames) frames.push_back(camera_json(c));
  json doc = {{"format", "cullcheck-path"}, {"version", 1},         {"kind", path.kind},
              {"seed", path.seed},          {"frames_per_second", number(path.frames_per_second)},
              {"frames", std::move(frames)}};
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
  const json& frames = member(doc, "frames", "path");
  if (!frames.is_array()) throw InputError("path", "frames", "must be an array");
  for (std::size_t i = 0; i < frames.size(); ++i) path.frames.push_back(camera_from(frames[i], "path frame " + std::to_string(i)));
  return path;
}

void write_obj(const Scene& scene, std::ostream& out) {
  out << "# cullcheck scene: generator " << scene.provenance.generator << ", seed " << scene.provenance.seed << ", "
      << scene.buildings.size() << " buildings\n";
  char line[128];
  std::size_t base = 1;
  for (const Building& b : scene.buildings) {
    out << "o building_" << b.id << "\n";
    const std::size_t n = b.footprint.size();
    for (Vec2 p : b.footprint) {
      std::snprintf(line, sizeof line, "v %.9g %.9g 0\nv %.9g %.9g %.9g\n", p.x, p.y, p.x, p.y, b.height);
      out << line;
    }
    for (std::size_t i = 0; i < n; ++i) {  // walls: bottom i, top i, bottom j, top j
      const std::size_t j = (i + 1) % n;
      const std::size_t bi = base + 2 * i, ti = bi + 1, bj = base + 2 * j, tj = bj + 1;
      out << "f " << bi << ' ' << bj << ' ' << tj << "\nf " << bi << ' ' << tj << ' ' << ti << "\n";
    }
    // Roof: one polygon face; viewers triangulate it (it may be non-convex).
    out << "f";
    for (std::size_t i = 0; i < n; ++i) out << ' ' << base + 2 * i + 1;
    out << "\n";
    base += 2 * n;
  }
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
