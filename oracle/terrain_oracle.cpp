#include "oracle/terrain_oracle.hpp"

#include <embree3/rtcore.h>

#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/parallel_indices.hpp"

namespace cullcheck::oracle {

struct TerrainOracle::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

// Barycentric distance from a triangle's boundary below which a hit does not witness it.
constexpr float kEdgeMargin = 1e-4f;

bool in_sector(double azimuth, const TerrainWitnessOptions& o) {
  if (!(o.sector_width < kTwoPi)) return true;
  const double from = o.sector_centre - 0.5 * o.sector_width;
  double offset = std::fmod(azimuth - from, kTwoPi);
  if (offset < 0) offset += kTwoPi;
  return offset <= o.sector_width;
}

Vec3 direction(double azimuth, double elevation) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
}

// Sample k of a triangle: the centroid of the k-th of its n x n sub-triangles (barycentric
// steps of 1/n; the upward ones of each row, then the downward ones between them).
Vec3 sample_point(const Vec3* v, int n, std::uint64_t k) {
  int i = 0;
  std::uint64_t row = 2 * std::uint64_t(n) - 1;  // sub-triangles in row i
  while (k >= row) k -= row, ++i, row -= 2;
  const int up = n - i;  // upward sub-triangles in this row
  const bool down = k >= std::uint64_t(up);
  const int j = int(down ? k - up : k);
  const double u = (3.0 * j + 1 + (down ? 1 : 0)) / (3.0 * n), w = (3.0 * i + 1 + (down ? 1 : 0)) / (3.0 * n);
  return v[0] + (v[1] - v[0]) * u + (v[2] - v[0]) * w;
}

}  // namespace

std::array<Vec3, 3> TerrainOracle::primitive(std::size_t p) const {
  std::array<Vec3, 3> v;
  for (int k = 0; k < 3; ++k) {
    const std::size_t i = indices_[3 * p + k];
    v[k] = Vec3{double(vertices_[3 * i]), double(vertices_[3 * i + 1]), double(vertices_[3 * i + 2])} + origin_;
  }
  return v;
}

TerrainOracle::TerrainOracle(const Terrain& t) : TerrainOracle(t, nullptr) {}

TerrainOracle::TerrainOracle(const TerrainScene& scene) : TerrainOracle(scene.terrain, &scene) {}

TerrainOracle::TerrainOracle(const Terrain& t, const TerrainScene* scene) : embree_(std::make_unique<Embree>()) {
  validate(t, "terrain");
  origin_ = {t.corner.x + 0.5 * (t.nx - 1) * t.dx, t.corner.y + 0.5 * (t.ny - 1) * t.dy, 0.0};
  // The vertices, from the grid's definition: vertex (i, j) at corner + (i dx, j dy).
  vertices_.resize(3 * std::size_t(t.nx) * t.ny);
  for (std::uint32_t j = 0; j < t.ny; ++j)
    for (std::uint32_t i = 0; i < t.nx; ++i) {
      const std::size_t v = std::size_t(j) * t.nx + i;
      const bool hole = !t.hole.empty() && t.hole[v];
      vertices_[3 * v] = float(t.corner.x + i * t.dx - origin_.x);
      vertices_[3 * v + 1] = float(t.corner.y + j * t.dy - origin_.y);
      vertices_[3 * v + 2] = hole ? 0.0f : float(t.z[v]);
    }
  // Two triangles a cell, numbered 2c and 2c + 1 for cell c = j (nx - 1) + i: the south-east
  // half (i,j) (i+1,j) (i+1,j+1) and the north-west half (i,j) (i+1,j+1) (i,j+1).
  for (std::uint32_t j = 0; j + 1 < t.ny; ++j)
    for (std::uint32_t i = 0; i + 1 < t.nx; ++i) {
      const std::uint32_t a = j * t.nx + i, b = a + 1, d = a + t.nx, c = d + 1;
      const std::uint32_t cell = j * (t.nx - 1) + i;
      const auto hole = [&](std::uint32_t v) { return !t.hole.empty() && t.hole[v]; };
      if (!hole(a) && !hole(b) && !hole(c)) numbers_.push_back(2 * cell), indices_.insert(indices_.end(), {a, b, c});
      if (!hole(a) && !hole(c) && !hole(d)) numbers_.push_back(2 * cell + 1), indices_.insert(indices_.end(), {a, c, d});
    }
  outward_.assign(numbers_.size(), 0);
  // Buildings (core/terrain_scene.hpp's numbering, after the terrain's 2 (nx - 1) (ny - 1)): per
  // prism its ring at the base and at the roof as new vertices, then its walls (two a ring edge,
  // lower then upper) and its roof fan from corner 0. Their winding faces outward.
  std::uint32_t number = 2 * (t.nx - 1) * (t.ny - 1);
  if (scene)
    for (const StandingBuilding& b : scene->buildings)
      for (const StandingPrism& prism : b.prisms) {
        const auto n = std::uint32_t(prism.ring.size());
        const auto first = std::uint32_t(vertices_.size() / 3);
        for (const double z : {prism.base, prism.roof})
          for (const Vec2& c : prism.ring)
            vertices_.insert(vertices_.end(), {float(c.x - origin_.x), float(c.y - origin_.y), float(z - origin_.z)});
        const auto low = [&](std::uint32_t k) { return first + k % n; };
        const auto high = [&](std::uint32_t k) { return first + n + k % n; };
        const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
          numbers_.push_back(number++);
          indices_.insert(indices_.end(), {a, b, c});
          outward_.push_back(1);
        };
        for (std::uint32_t k = 0; k < n; ++k) add(low(k), low(k + 1), high(k + 1)), add(low(k), high(k + 1), high(k));
        for (std::uint32_t k = 1; k + 1 < n; ++k) add(high(0), high(k), high(k + 1));
      }
  embree_->device = rtcNewDevice("threads=1,set_affinity=0,verbose=0");
  if (!embree_->device) throw std::runtime_error("Embree: rtcNewDevice failed");
  embree_->scene = rtcNewScene(embree_->device);
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry g = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Shared buffers: the oracle keeps them alive as long as the scene.
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices_.data(), 0, 3 * sizeof(float),
                             vertices_.size() / 3);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices_.data(), 0, 3 * sizeof(std::uint32_t),
                             numbers_.size());
  rtcCommitGeometry(g);
  rtcAttachGeometry(embree_->scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(embree_->scene);
  if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE) throw std::runtime_error("Embree: building the terrain scene failed");
}

TerrainOracle::~TerrainOracle() = default;

std::int64_t TerrainOracle::first_hit(Vec3 from, Vec3 d, double t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = float(from.x - origin_.x), rh.ray.org_y = float(from.y - origin_.y), rh.ray.org_z = float(from.z - origin_.z);
  rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = float(t_far);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(embree_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
  // A hit on (or within rounding of) the triangle's boundary proves nothing about its inside: a
  // line of sight grazing a ridge touches the edge of the triangle behind it, seen from below.
  const float u = rh.hit.u, v = rh.hit.v;
  if (!(u > kEdgeMargin && v > kEdgeMargin && 1.0f - u - v > kEdgeMargin)) return -1;
  // Only the upper side is terrain: a line of sight meeting a triangle from below came in through
  // a NoData hole, under the ground, and sees nothing (it still stops there). A building's
  // triangle is seen from outside only (its winding says which side that is).
  const auto tri = primitive(rh.hit.primID);
  Vec3 up = cross(tri[1] - tri[0], tri[2] - tri[0]);
  if (!outward_[rh.hit.primID] && up.z < 0.0) up = up * -1.0;
  if (!(dot(up, d) < 0.0)) return -1;
  return std::int64_t(numbers_[rh.hit.primID]);
}

TerrainWitness TerrainOracle::witnessed(Vec3 eye, const TerrainWitnessOptions& o) const {
  if (o.subdivisions < 0 || o.subdivisions > 16) throw std::invalid_argument("TerrainOracle: subdivisions must lie in [0, 16]");
  std::uint32_t largest = 0;
  for (std::uint32_t n : numbers_) largest = std::max(largest, n);
  // Per triangle, the smallest ray number that hit it first (rays numbered in the oracle's
  // order: samples by primitive, then the sphere lattice), so the witness is the same on any
  // number of threads.
  constexpr std::uint64_t kNone = ~std::uint64_t(0);
  std::vector<std::uint64_t> seen(std::size_t(largest) + 1, kNone);
  const auto mark = [&](std::int64_t hit, std::uint64_t ray) {
    if (hit < 0) return;
    std::atomic_ref<std::uint64_t> slot(seen[std::size_t(hit)]);
    std::uint64_t now = slot.load(std::memory_order_relaxed);
    while (ray < now && !slot.compare_exchange_weak(now, ray, std::memory_order_relaxed)) {
    }
  };
  const std::uint64_t per_triangle = std::uint64_t(o.subdivisions) * o.subdivisions;
  const int n = o.subdivisions;
  constexpr std::size_t kBlock = 4096;
  const std::size_t blocks = (numbers_.size() + kBlock - 1) / kBlock;
  const std::size_t sphere = std::size_t(o.sphere_azimuths) * o.sphere_elevations;
  std::vector<std::uint64_t> rays(blocks + 1, 0);
  for_each_index(blocks + 1, o.threads, [&] {
    return [&](std::size_t block) {
      std::uint64_t cast = 0;
      if (block == blocks) {  // the sphere lattice, cell centres in azimuth and elevation
        for (std::size_t k = 0; k < sphere; ++k) {
          const double azimuth = kTwoPi * (double(k % o.sphere_azimuths) + 0.5) / o.sphere_azimuths;
          const double elevation = kPi * (double(k / o.sphere_azimuths) + 0.5) / o.sphere_elevations - 0.5 * kPi;
          if (!in_sector(azimuth, o)) continue;
          mark(first_hit(eye, direction(azimuth, elevation), HUGE_VAL), per_triangle * numbers_.size() + k);
          ++cast;
        }
        rays[block] = cast;
        return;
      }
      for (std::size_t p = block * kBlock; p < std::min(numbers_.size(), (block + 1) * kBlock); ++p) {
        const std::array<Vec3, 3> v = primitive(p);
        for (std::uint64_t k = 0; k < per_triangle; ++k) {
          const Vec3 d = sample_point(v.data(), n, k) - eye;
          if (!in_sector(azimuth_of(plan(d)), o)) continue;
          mark(first_hit(eye, d, 1.0 + 1e-4), per_triangle * p + k);
          ++cast;
        }
      }
      rays[block] = cast;
    };
  });
  TerrainWitness out;
  for (std::uint64_t r : rays) out.rays += r;
  for (std::size_t t = 0; t < seen.size(); ++t) {
    if (seen[t] == kNone) continue;
    out.witnessed.push_back(std::uint32_t(t));
    const std::uint64_t ray = seen[t], p = ray / per_triangle, k = ray % per_triangle;
    if (p < numbers_.size()) {
      out.witness_points.push_back(sample_point(primitive(p).data(), n, k));
    } else {  // a lattice ray: the point one unit along it
      const std::uint64_t l = ray - per_triangle * numbers_.size();
      const double azimuth = kTwoPi * (double(l % o.sphere_azimuths) + 0.5) / o.sphere_azimuths;
      const double elevation = kPi * (double(l / o.sphere_azimuths) + 0.5) / o.sphere_elevations - 0.5 * kPi;
      out.witness_points.push_back(eye + direction(azimuth, elevation));
    }
  }
  return out;
}

}  // namespace cullcheck::oracle
