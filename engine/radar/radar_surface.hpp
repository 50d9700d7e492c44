// What the radar sees: a terrain's triangles (core/terrain.hpp), and the triangles of the
// buildings standing on it (core/terrain_scene.hpp), numbered after the terrain's.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "core/terrain.hpp"
#include "core/terrain_scene.hpp"

namespace cullcheck::radar {

class RadarSurface {
 public:
  // The terrain alone, or a terrain with its buildings; either must outlive the surface.
  RadarSurface(const Terrain& terrain);  // NOLINT: a terrain is a surface
  explicit RadarSurface(const TerrainScene& scene);

  const Terrain& terrain() const { return *terrain_; }
  std::size_t triangle_count() const { return terrain_triangles_ + buildings_.size(); }
  std::size_t terrain_triangles() const { return terrain_triangles_; }
  std::size_t present_triangle_count() const { return present_; }
  bool present(std::size_t t) const { return t >= terrain_triangles_ || terrain_->triangle_present(t); }
  std::array<Vec3, 3> triangle(std::size_t t) const {
    return t < terrain_triangles_ ? terrain_->triangle(t) : buildings_[t - terrain_triangles_];
  }
  // The building (its index in the scene) a triangle belongs to, -1 for the terrain's.
  std::int64_t building_of(std::size_t t) const { return t < terrain_triangles_ ? -1 : std::int64_t(owner_[t - terrain_triangles_]); }
  bool terrain_has_holes() const { return terrain_->present_triangle_count() < terrain_triangles_; }

 private:
  const Terrain* terrain_;
  std::size_t terrain_triangles_;
  std::size_t present_;
  std::vector<std::array<Vec3, 3>> buildings_;
  std::vector<std::uint32_t> owner_;
};

}  // namespace cullcheck::radar
