#include "core/formats/footprint_rings.hpp"

#include <cmath>
#include <cstddef>

#include "core/scene.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {

std::vector<Vec2> cleaned_ring(std::vector<Vec2> ring, bool& changed) {
  changed = false;
  while (ring.size() >= 2 && ring.front() == ring.back()) ring.pop_back();
  for (bool again = true; again && ring.size() >= 3;) {
    again = false;
    for (std::size_t i = 0; i < ring.size() && ring.size() >= 3; ++i) {
      const std::size_t n = ring.size();
      const Vec2 a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
      const Vec2 in = b - a, out = c - b;
      const bool repeated = b == c;
      const bool spike = cross(in, out) == 0.0 && dot(in, out) < 0.0;
      if (repeated || spike) {
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
        changed = again = true;
        break;
      }
    }
  }
  return ring;
}

std::string footprint_problem(const std::vector<Vec2>& ring) {
  if (ring.size() < 3) return "fewer than 3 distinct vertices";
  if (ring.size() > kMaxFootprintVertices) return "more than 4096 vertices";
  if (!is_simple(ring)) return "edges cross or touch";
  if (!(std::abs(signed_area(ring)) > 0.0)) return "zero area";
  return "";
}

}  // namespace cullcheck::formats
