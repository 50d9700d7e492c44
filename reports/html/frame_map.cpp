#include "reports/html/frame_map.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/pictures.hpp"

namespace cullcheck::html {
namespace {

const Box3* bounds_of(const Scene& scene, ObjectId id) {
  if (const Building* b = scene.find(id)) return &b->bounds;
  if (const MeshObject* m = scene.find_mesh(id)) return &m->bounds;
  return nullptr;
}

nlohmann::json vec3_json(Vec3 v) { return {v.x, v.y, v.z}; }

Vec3 vec3_of(const nlohmann::json& j, const std::string& field) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw InputError("report map", field, "is not an array of three numbers");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

std::vector<ObjectId> ids_of(const nlohmann::json& map, const std::string& field, const Scene& scene) {
  const auto it = map.find(field);
  if (it == map.end() || !it->is_array()) throw InputError("report map", field, "is missing or not an array of object ids");
  std::vector<ObjectId> ids;
  for (const auto& v : *it) {
    if (!v.is_number_integer() || v.get<std::int64_t>() < 0 || v.get<std::int64_t>() > std::int64_t(UINT32_MAX))
      throw InputError("report map", field, "holds something that is not an object id");
    const ObjectId id = ObjectId(v.get<std::int64_t>());
    if (bounds_of(scene, id) == nullptr)
      throw InputError("report map", field,
                       "names object " + std::to_string(id) + ", which the scene does not have (is it the report's scene?)");
    ids.push_back(id);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<oracle::WitnessRay> rays_of(const nlohmann::json& map) {
  std::vector<oracle::WitnessRay> rays;
  const auto it = map.find("witness_rays");
  if (it == map.end()) return rays;
  if (!it->is_array()) throw InputError("report map", "witness_rays", "is not an array");
  for (const auto& r : *it) {
    if (!r.is_object() || !r.contains("origin") || !r.contains("hit"))
      throw InputError("report map", "witness_rays", "holds a ray without \"origin\" and \"hit\"");
    oracle::WitnessRay ray;
    ray.origin = vec3_of(r["origin"], "witness_rays[].origin");
    ray.hit_point = vec3_of(r["hit"], "witness_rays[].hit");
    rays.push_back(ray);
  }
  return rays;
}

Camera camera_of(const nlohmann::json& map) {
  if (!map.is_object() || !map.contains("camera")) throw InputError("report map", "camera", "is missing");
  return camera_from_json_text(map["camera"].dump(), "report map camera");
}

}  // namespace

const MethodRun* choose_map_run(const PathVerification& v, const std::string& method, const std::string& reference) {
  if (!method.empty()) {
    std::string names;
    for (const MethodRun& r : v.runs) {
      if (r.method == method) {
        if (!r.snapshot) throw std::invalid_argument("--map-method " + method + ": the method has no frame checked by the oracle");
        return &r;
      }
      names += (names.empty() ? "" : ", ") + r.method;
    }
    throw std::invalid_argument("--map-method " + method + " is not a method of this run (" + names + ")");
  }
  const MethodRun* worst = nullptr;
  auto rank = [](const MethodRun& r) { return std::make_pair(r.claims_conservative ? 1 : 0, r.snapshot->missed.size()); };
  for (const MethodRun& r : v.runs)
    if (r.snapshot && !r.snapshot->missed.empty() && (!worst || rank(r) > rank(*worst))) worst = &r;
  if (worst) return worst;
  for (const MethodRun& r : v.runs)
    if (r.snapshot && r.method == reference) return &r;
  for (const MethodRun& r : v.runs)
    if (r.snapshot) return &r;
  return nullptr;
}

nlohmann::json map_json(const MethodRun& run, const std::string& chosen_by) {
  const FrameSnapshot& s = *run.snapshot;
  nlohmann::json rays = nlohmann::json::array();
  for (const oracle::WitnessRay& r : s.witness_rays) rays.push_back({{"origin", vec3_json(r.origin)}, {"hit", vec3_json(r.hit_point)}});
  return {{"method", run.method},
          {"frame", s.frame},
          {"chosen_by", chosen_by},
          {"camera", nlohmann::json::parse(camera_to_json_text(s.camera))},
          {"pvs", s.pvs},
          {"seen", s.seen},
          {"missed", s.missed},
          {"overestimate", s.overestimate},
          {"witness_rays", rays}};
}

Box2 map_extent(const Scene& scene, const nlohmann::json& map, double min_half_span) {
  const Camera camera = camera_of(map);
  const Vec2 eye = plan(camera.position);
  Box2 box;
  box.extend(eye - Vec2{min_half_span, min_half_span});
  box.extend(eye + Vec2{min_half_span, min_half_span});
  for (const char* field : {"seen", "missed"})
    for (ObjectId id : ids_of(map, field, scene)) {
      const Box3* b = bounds_of(scene, id);
      if (b) box.extend(b->plan().lo), box.extend(b->plan().hi);
    }
  for (const oracle::WitnessRay& r : rays_of(map)) box.extend(plan(r.hit_point));
  // A street's view is long and thin: widen the shorter side to 60% of the longer, so the
  // blocks beside the street show and the picture is not a sliver.
  const Vec2 centre = box.center();
  const double w = box.hi.x - box.lo.x, h = box.hi.y - box.lo.y, least = 0.6 * std::max(w, h);
  if (w < least) box.lo.x = centre.x - least / 2, box.hi.x = centre.x + least / 2;
  if (h < least) box.lo.y = centre.y - least / 2, box.hi.y = centre.y + least / 2;
  return box;
}

std::string map_png(const Scene& scene, const nlohmann::json& map, int size_px) {
  const Camera camera = camera_of(map);
  const MapFrame frame = map_frame_of(map_extent(scene, map), size_px);
  return encode_png(top_down_map(scene, camera, ids_of(map, "pvs", scene), ids_of(map, "seen", scene),
                                 ids_of(map, "missed", scene), rays_of(map), frame));
}

}  // namespace cullcheck::html
