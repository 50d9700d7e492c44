#include "core/scene_timeline.hpp"

#include <algorithm>
#include <map>
#include <string>

#include "core/errors.hpp"

namespace cullcheck {

std::set<ObjectId> absent_at_start(const CameraPath& path) {
  std::map<ObjectId, bool> first;  // id -> its first event is an appearance
  for (const SceneEvent& e : path.events) {
    for (ObjectId id : e.appear) first.emplace(id, true);
    for (ObjectId id : e.vanish) first.emplace(id, false);
  }
  std::set<ObjectId> absent;
  for (const auto& [id, appears] : first)
    if (appears) absent.insert(id);
  return absent;
}

void validate_timeline(const CameraPath& path, const Scene& scene, std::size_t frames) {
  const std::vector<ObjectId> ids = scene.ids();
  std::set<ObjectId> absent = absent_at_start(path);
  for (std::size_t i = 0; i < path.events.size(); ++i) {
    const SceneEvent& e = path.events[i];
    const std::string object = "path event " + std::to_string(i);
    if (e.frame >= frames) throw InputError(object, "frame", std::to_string(e.frame) + " is past the path's " + std::to_string(frames) + " frames");
    if (i > 0 && e.frame <= path.events[i - 1].frame)
      throw InputError(object, "frame", std::to_string(e.frame) + " is not after the previous event's frame " + std::to_string(path.events[i - 1].frame));
    if (e.appear.empty() && e.vanish.empty()) throw InputError(object, "(event)", "makes nothing appear or vanish");
    for (const char* key : {"appear", "vanish"}) {
      const bool appear = std::string(key) == "appear";
      for (ObjectId id : appear ? e.appear : e.vanish) {
        if (!std::binary_search(ids.begin(), ids.end(), id))
          throw InputError(object, key, "object " + std::to_string(id) + " is not in the scene (a timeline's objects must all be in it)");
        const bool is_absent = absent.count(id) > 0;
        if (appear && !is_absent) throw InputError(object, key, "object " + std::to_string(id) + " is already present");
        if (!appear && is_absent) throw InputError(object, key, "object " + std::to_string(id) + " is already absent");
      }
    }
    for (ObjectId id : e.appear) absent.erase(id);
    for (ObjectId id : e.vanish) absent.insert(id);
  }
}

Scene present_scene(const Scene& scene, const std::set<ObjectId>& absent) {
  Scene out;
  out.provenance = scene.provenance;
  out.origin = scene.origin;
  for (const Building& b : scene.buildings)
    if (!absent.count(b.id)) out.buildings.push_back(b);
  for (const MeshObject& m : scene.meshes)
    if (!absent.count(m.id)) out.meshes.push_back(m);
  return out;
}

const Scene& PresentScenes::apply(const std::vector<ObjectId>& appear, const std::vector<ObjectId>& vanish) {
  for (ObjectId id : vanish) absent_.insert(id);
  for (ObjectId id : appear) absent_.erase(id);
  kept_.push_back(present_scene(scene_, absent_));
  return kept_.back();
}

}  // namespace cullcheck
