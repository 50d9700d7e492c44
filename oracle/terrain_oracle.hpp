// The oracle over terrain (radar echo, thesis ch. 3.3): Embree first hits from the transmitter
// into the terrain mesh. A triangle is witnessed visible when some ray from the transmitter hits
// it first; the witnessed set is a lower bound of the truly visible set, and grows with the
// sample density. Rays go towards sample points inside every present triangle (the centroids of
// its n x n sub-triangles) and, optionally, through a stratified lattice over the full sphere
// of directions. A hit within 1e-4 (barycentric) of a triangle's boundary witnesses nothing: a
// line of sight that only touches a triangle's edge (grazing a ridge, it touches the triangle
// behind the ridge, seen from below) sees none of its area. Nor does a hit on a triangle's lower
// side: the terrain is the top of the ground, and a line of sight that meets a triangle from
// below entered the ground through a NoData hole (it still stops there).
//
// Independence from the engine (design: "Oracle"): the oracle builds its own triangles from the
// terrain's heights and the numbering documented in core/terrain.hpp; it calls none of
// Terrain's triangle helpers nor anything in engine/.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/geometry.hpp"
#include "core/terrain.hpp"
#include "core/terrain_scene.hpp"

namespace cullcheck::oracle {

struct TerrainWitnessOptions {
  int subdivisions = 2;            // samples per triangle: subdivisions^2 sub-triangle centroids
  std::uint32_t sphere_azimuths = 0;    // lattice rays over the sphere: azimuths x elevations (0: none)
  std::uint32_t sphere_elevations = 0;
  double sector_centre = 0.0;      // azimuths witnessed: the sector [centre - width/2, centre + width/2]
  double sector_width = kTwoPi;    // 2π: the full circle
  unsigned threads = 0;            // 0: every core; the result does not depend on it
};

struct TerrainWitness {
  std::vector<std::uint32_t> witnessed;  // triangle numbers, ascending
  std::vector<Vec3> witness_points;      // per witnessed triangle: the point its ray aimed at (the
                                         // first ray in the oracle's order that hit it first)
  std::uint64_t rays = 0;
};

class TerrainOracle {
 public:
  explicit TerrainOracle(const Terrain& terrain);
  // The terrain and the buildings standing on it (their triangles numbered as
  // core/terrain_scene.hpp documents, built here from the prisms' rings and heights).
  explicit TerrainOracle(const TerrainScene& scene);
  ~TerrainOracle();
  TerrainOracle(const TerrainOracle&) = delete;
  TerrainOracle& operator=(const TerrainOracle&) = delete;

  TerrainWitness witnessed(Vec3 transmitter, const TerrainWitnessOptions& options = {}) const;
  // The triangle number first hit by the ray from `from` along `direction` within `t_far` (in
  // direction lengths), or -1 (also when the hit lies on the triangle's boundary).
  std::int64_t first_hit(Vec3 from, Vec3 direction, double t_far) const;
  std::size_t triangles() const { return numbers_.size(); }  // present triangles in the mesh

 private:
  TerrainOracle(const Terrain& terrain, const TerrainScene* scene);
  std::array<Vec3, 3> primitive(std::size_t p) const;  // its vertices, as the mesh holds them
  struct Embree;
  std::unique_ptr<Embree> embree_;
  Vec3 origin_;                          // subtracted before rounding to floats
  std::vector<std::uint32_t> numbers_;   // Embree primitive -> triangle number
  std::vector<float> vertices_;          // xyz per vertex, relative to origin_
  std::vector<std::uint32_t> indices_;   // 3 per primitive
  std::vector<std::uint8_t> outward_;    // per primitive: 1 for a building's (its winding faces out)
};

}  // namespace cullcheck::oracle
