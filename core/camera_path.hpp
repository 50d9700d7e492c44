// A camera path: one camera per frame at a fixed frame rate (street walks, fly-throughs).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.hpp"

namespace cullcheck {

struct CameraPath {
  std::string kind;      // e.g. "street_walk", "fly_through"
  std::uint64_t seed = 0;
  double frames_per_second = 30.0;
  std::vector<Camera> frames;
};

}  // namespace cullcheck
