// A camera path: one camera per frame at a fixed frame rate (street walks, fly-throughs).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.hpp"

namespace cullcheck {

// The frame a camera or path file gives positions in (core/coordinates.hpp): scene-local metres,
// or world metres (local + Scene::origin; far scenes are rebased on load).
enum class CoordinateFrame : std::uint8_t { local, world };

struct CameraPath {
  std::string kind;      // e.g. "street_walk", "fly_through"
  std::uint64_t seed = 0;
  double frames_per_second = 30.0;
  std::vector<Camera> frames;
  // What the file says of its frame ("coordinates", and with local ones the "origin" they are
  // local to); unset when it says nothing. to_scene_local (core/coordinates.hpp) resolves it.
  std::optional<CoordinateFrame> coordinates;
  std::optional<Vec2> origin;
};

}  // namespace cullcheck
