#include "engine/radar/radar_surface.hpp"

namespace cullcheck::radar {

RadarSurface::RadarSurface(const Terrain& terrain)
    : terrain_(&terrain), terrain_triangles_(terrain.triangle_count()), present_(terrain.present_triangle_count()) {}

RadarSurface::RadarSurface(const TerrainScene& scene) : RadarSurface(scene.terrain) {
  for (std::size_t b = 0; b < scene.buildings.size(); ++b)
    for (const StandingPrism& p : scene.buildings[b].prisms) {
      const std::size_t n = p.ring.size();
      const auto at = [&](std::size_t k, double z) { return Vec3{p.ring[k % n].x, p.ring[k % n].y, z}; };
      for (std::size_t k = 0; k < n; ++k) {  // walls: lower, then upper triangle
        buildings_.push_back({at(k, p.base), at(k + 1, p.base), at(k + 1, p.roof)});
        buildings_.push_back({at(k, p.base), at(k + 1, p.roof), at(k, p.roof)});
      }
      for (std::size_t k = 1; k + 1 < n; ++k) buildings_.push_back({at(0, p.roof), at(k, p.roof), at(k + 1, p.roof)});
      owner_.resize(buildings_.size(), std::uint32_t(b));
    }
  present_ += buildings_.size();
}

}  // namespace cullcheck::radar
