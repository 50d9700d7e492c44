// Shared import rules (import_objects.hpp).
#include "core/formats/import_objects.hpp"

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats::detail {
namespace {

constexpr std::uint64_t kMaxId = 0xFFFFFFFFULL;

// A given prism is used only when the mesh it came with lies on its surface, within the prism
// tolerance of mesh_formats.hpp: a node moved in an editor after export keeps stale extras, and
// then the mesh, not the extras, is the truth.
bool prism_matches_mesh(const Building& b, const MeshObject& m) {
  double scale = 1.0;
  for (const Vec3& v : m.vertices) scale = std::max({scale, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  const double tol = kPrismTolerance * scale;
  const Box3 &p = b.bounds, &q = m.bounds;
  if (std::abs(p.lo.x - q.lo.x) > tol || std::abs(p.lo.y - q.lo.y) > tol || std::abs(p.lo.z - q.lo.z) > tol ||
      std::abs(p.hi.x - q.hi.x) > tol || std::abs(p.hi.y - q.hi.y) > tol || std::abs(p.hi.z - q.hi.z) > tol)
    return false;
  const std::size_t n = b.footprint.size();
  for (const auto& t : m.triangles)
    for (std::uint32_t k : t) {
      const Vec3 v = m.vertices[k];
      if (std::abs(v.z) > tol && std::abs(v.z - b.height) > tol) return false;
      bool on_outline = false;
      for (std::size_t i = 0; i < n && !on_outline; ++i)
        on_outline = distance_to_segment({v.x, v.y}, b.footprint[i], b.footprint[(i + 1) % n]) <= tol;
      if (!on_outline) return false;
    }
  return true;
}

}  // namespace

std::optional<ObjectId> id_from_name(const std::string& name, const std::string& object) {
  std::string digits;
  for (const char* prefix : {"building_", "mesh_", "object_"})
    if (name.rfind(prefix, 0) == 0) digits = name.substr(std::char_traits<char>::length(prefix));
  if (digits.empty()) digits = name;
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const std::size_t first = std::min(digits.find_first_not_of('0'), digits.size() - 1);
  if (digits.size() - first > 10 || std::stoull(digits.substr(first)) > kMaxId)
    throw InputError(object, "name", "names the id " + digits + ", beyond the largest id 4294967295");
  return static_cast<ObjectId>(std::stoull(digits.substr(first)));
}

GivenExtras parse_given_extras(const std::string& extras_json, const std::string& object) {
  GivenExtras given;
  if (extras_json.empty()) return given;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(extras_json);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(object, "extras", std::string("is not valid JSON: ") + e.what());
  }
  if (!j.is_object()) return given;  // extras of other tools: anything goes
  if (auto it = j.find("cullcheck_id"); it != j.end()) {
    const bool integral = it->is_number_unsigned() ||
                          (it->is_number_float() && std::floor(it->get<double>()) == it->get<double>() && it->get<double>() >= 0);
    if (!integral || it->get<double>() > static_cast<double>(kMaxId))
      throw InputError(object, "extras.cullcheck_id", "must be an integer in [0, 2^32) (got " + it->dump() + ")");
    given.id = it->is_number_unsigned() ? it->get<std::uint64_t>() : static_cast<std::uint64_t>(it->get<double>());
  }
  if (auto it = j.find("kind"); it != j.end()) {
    if (*it != "building" && *it != "mesh")
      throw InputError(object, "extras.kind", "must be \"building\" or \"mesh\" (got " + it->dump() + ")");
    given.kind_mesh = *it == "mesh";
  }
  if (auto it = j.find("name"); it != j.end()) {
    if (!it->is_string()) throw InputError(object, "extras.name", "must be a string");
    given.name = it->get<std::string>();
  }
  const auto fp = j.find("footprint");
  const auto height = j.find("height");
  if ((fp == j.end()) != (height == j.end()))
    throw InputError(object, fp == j.end() ? "extras.footprint" : "extras.height",
                     "is missing (footprint and height come together)");
  if (fp != j.end()) {
    Building b;
    b.id = static_cast<ObjectId>(given.id.value_or(0));
    if (!height->is_number()) throw InputError(object, "extras.height", "must be a number");
    b.height = height->get<double>();
    if (!fp->is_array() || fp->size() > kMaxFootprintVertices + 1)
      throw InputError(object, "extras.footprint", "must be an array of at most 4096 [x, y] pairs");
    for (std::size_t k = 0; k < fp->size(); ++k) {
      const nlohmann::json& p = (*fp)[k];
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
        throw InputError(object, "extras.footprint[" + std::to_string(k) + "]", "must be [x, y]");
      b.footprint.push_back({p[0].get<double>(), p[1].get<double>()});
    }
    given.prism = std::move(b);
  }
  return given;
}

Scene finish_import(std::vector<ImportedObject> objects, Scene scene, const ImportOptions& options,
                    ImportReport* report, const std::string& file) {
  if (objects.empty()) throw InputError(file, "(scene)", "holds no object with triangles");
  if (objects.size() > kMaxMeshes) throw InputError(file, "(scene)", "holds more than 20,000,000 objects");

  // Ids: given or named first, then the next free ones in file order.
  std::map<ObjectId, std::size_t> owner;
  std::vector<std::optional<ObjectId>> ids(objects.size());
  std::uint64_t next = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ImportedObject& o = objects[i];
    const std::string where = file + ": " + o.source;
    if (o.given.id) ids[i] = static_cast<ObjectId>(*o.given.id);
    else ids[i] = id_from_name(o.name, where);
    if (!ids[i]) continue;
    auto [it, added] = owner.emplace(*ids[i], i);
    if (!added)
      throw InputError(where, o.given.id ? "extras.cullcheck_id" : "name",
                       "gives id " + std::to_string(*ids[i]) + ", which " + objects[it->second].source + " has already");
    next = std::max<std::uint64_t>(next, std::uint64_t{*ids[i]} + 1);
  }
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (ids[i]) continue;
    if (next > kMaxId) throw InputError(file + ": " + objects[i].source, "id", "no free id is left below 2^32");
    ids[i] = static_cast<ObjectId>(next++);
  }

  ImportReport local;
  ImportReport& r = report ? *report : local;
  r.objects = objects.size();
  scene.meshes.reserve(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    MeshObject& m = objects[i].mesh;
    m.id = *ids[i];
    m.name = objects[i].given.name.value_or(objects[i].name);
    if (objects[i].given.prism) objects[i].given.prism->id = m.id;
    try {
      r.degenerate_triangles_dropped += validate_and_finish(m, true);
    } catch (const InputError& e) {
      throw InputError(file + ": " + objects[i].source + " (id " + std::to_string(m.id) + ")", e.field(), e.problem());
    }
    scene.meshes.push_back(std::move(m));
  }

  // Rebase while everything is still a mesh; given footprints move with their meshes.
  const Vec2 before = scene.origin;
  rebase_if_far(scene);
  const Vec2 shift = scene.origin - before;

  std::vector<MeshObject> kept;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    MeshObject& m = scene.meshes[i];
    const ImportedObject& o = objects[i];
    std::optional<Building> b;
    if (options.detect_prisms && !o.given.kind_mesh) {
      if (o.given.prism) {
        Building given = *o.given.prism;
        for (Vec2& p : given.footprint) p = p - shift;
        try {
          validate_and_finish(given);
          if (prism_matches_mesh(given, m)) b = std::move(given), ++r.prisms_given;
          else r.notes.push_back(o.source + ": extras footprint/height do not match its mesh; the mesh was used");
        } catch (const InputError& e) {
          throw InputError(file + ": " + o.source, "extras." + e.field(), e.problem());
        }
      }
      if (!b && (b = as_vertical_prism(m))) ++r.prisms_detected;
    }
    if (b) scene.buildings.push_back(std::move(*b));
    else kept.push_back(std::move(m));
  }
  r.meshes_kept = kept.size();
  scene.meshes = std::move(kept);
  return scene;
}

}  // namespace cullcheck::formats::detail
