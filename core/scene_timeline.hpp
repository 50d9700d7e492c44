// A camera path's scene timeline (core/camera_path.hpp: SceneEvent) against its scene: the
// checks a timeline must pass, the objects present at each frame, and the scene of the present
// objects that the oracle and the methods that cannot follow a change are rebuilt on.
#pragma once

#include <deque>
#include <set>

#include "core/camera_path.hpp"
#include "core/scene.hpp"

namespace cullcheck {

// Throws InputError naming "path event I" and the field when an event's frame is past the path
// (`frames` frames; a part of a longer path gives the whole path's count) or not after the
// previous event's, names an object the scene lacks, makes a present object appear or an absent
// one vanish, or is empty.
void validate_timeline(const CameraPath& path, const Scene& scene, std::size_t frames);

// The objects absent at frame 0: those whose first event makes them appear.
std::set<ObjectId> absent_at_start(const CameraPath& path);

// The scene without the `absent` objects (same origin and provenance).
Scene present_scene(const Scene& scene, const std::set<ObjectId>& absent);

// A walk's scene as its timeline changes it: `apply` records an event and returns the present
// scene, kept alive (with every earlier one) as long as this object, because the methods and
// the oracle rebuilt on it hold references to it.
class PresentScenes {
 public:
  explicit PresentScenes(const Scene& scene) : scene_(scene) {}
  const Scene& apply(const std::vector<ObjectId>& appear, const std::vector<ObjectId>& vanish);
  const std::set<ObjectId>& absent() const { return absent_; }

 private:
  const Scene& scene_;
  std::set<ObjectId> absent_;
  std::deque<Scene> kept_;
};

}  // namespace cullcheck
