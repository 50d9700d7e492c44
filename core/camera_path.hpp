// A camera path: one camera per frame at a fixed frame rate (street walks, fly-throughs).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"

namespace cullcheck {

// The frame a camera or path file gives positions in (core/coordinates.hpp): scene-local metres,
// or world metres (local + Scene::origin; far scenes are rebased on load).
enum class CoordinateFrame : std::uint8_t { local, world };

// A scene timeline (dynamic scenes, Wang et al. 2001 section 6): objects of the scene that
// vanish or appear from a frame on (core/scene_timeline.hpp). The scene holds every object that
// ever exists; one whose first event is an appearance is absent before it.
struct SceneEvent {
  std::size_t frame = 0;
  std::vector<ObjectId> appear, vanish;  // ascending
  friend bool operator==(const SceneEvent&, const SceneEvent&) = default;
};

struct CameraPath {
  std::string kind;      // e.g. "street_walk", "fly_through"
  std::uint64_t seed = 0;
  double frames_per_second = 30.0;
  std::vector<Camera> frames;
  std::vector<SceneEvent> events;  // ascending frames, at most one event per frame
  // What the file says of its frame ("coordinates", and with local ones the "origin" they are
  // local to); unset when it says nothing. to_scene_local (core/coordinates.hpp) resolves it.
  std::optional<CoordinateFrame> coordinates;
  std::optional<Vec2> origin;
};

}  // namespace cullcheck
