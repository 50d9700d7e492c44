#include "oracle/ray_plan.hpp"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "oracle/embree_scene.hpp"
#include "oracle/surface_samples.hpp"

namespace cullcheck::oracle {
namespace {

// The graze distance's floor relative to a point's distance from the mesh origin: 1e-6 is about
// 16 float ulps (2^-24 ~ 6e-8), so Embree sees the ray on the intended side of the edge.
constexpr double kGrazeFloorRelative = 1e-6;

// Which way a face looks, as the eye sees it: +1 toward the eye, -1 away, 0 edge-on.
int facing(double toward_eye) { return toward_eye > 0.0 ? 1 : toward_eye < 0.0 ? -1 : 0; }
bool silhouette(int a, int b) { return a == 0 || b == 0 || a != b; }

}  // namespace

ViewCone::ViewCone(const Camera& c)
    : transform_(c), forward_(transform_.forward()), near_(c.near), far_(c.far), orthographic_(c.orthographic()) {}

bool ViewCone::ortho_ray_toward(Vec3 p, PlannedRay& out, bool to_far) const {
  const Clip c = transform_.clip(p);  // w = 1: x and y are the view box's normalised coordinates
  if (std::abs(c.x) > 1.0 || std::abs(c.y) > 1.0) return false;
  const double depth = c.z - near_;  // from the near plane
  if (!(depth >= 0.0)) return false;  // before the near plane: clipped
  out.origin = p - forward_ * depth;
  out.direction = forward_;
  out.t_near = 0.0;
  out.t_far = far_ - near_;
  if (!to_far) out.t_far = std::min(out.t_far, depth * (1.0 + kBeyondRelative) + kBeyondAbsolute);
  out.target = p;
  return out.t_far > out.t_near;
}

namespace {

// out[i] = sqrt(in[i]) and out[i] = numerator / in[i] over a run: correctly rounded IEEE
// operations, so two lanes at a time (SSE2, on every x86-64) give the scalar results bit for bit.
void sqrt_run(const double* in, double* out, std::size_t n) {
  std::size_t i = 0;
#if defined(__SSE2__)
  for (; i + 2 <= n; i += 2) _mm_storeu_pd(out + i, _mm_sqrt_pd(_mm_loadu_pd(in + i)));
#endif
  for (; i < n; ++i) out[i] = std::sqrt(in[i]);
}
void divide_run(double numerator, const double* in, double* out, std::size_t n) {
  std::size_t i = 0;
#if defined(__SSE2__)
  const __m128d top = _mm_set1_pd(numerator);
  for (; i + 2 <= n; i += 2) _mm_storeu_pd(out + i, _mm_div_pd(top, _mm_loadu_pd(in + i)));
#endif
  for (; i < n; ++i) out[i] = numerator / in[i];
}

}  // namespace

ViewCone::BoxSettles ViewCone::settles(const Box3& box) const {
  BoxSettles out;
  if (orthographic_ || transform_.omnidirectional() || !(box.lo.x <= box.hi.x)) return out;
  const Vec3 eye = transform_.eye();
  const auto& planes = transform_.planes();
  // Per plane n (through the eye), over the box: the least value of n . (p - eye) (at the corner
  // the gradient points away from) against the largest sum of |n_k (p - eye)_k|, which bounds
  // the rounding of n . d for every d ray_toward computes toward a point of the box (each term
  // of n . d carries a relative error of a few 1e-16; 1e-9 leaves a wide margin).
  const Vec3 far_side{std::max(std::abs(box.lo.x - eye.x), std::abs(box.hi.x - eye.x)),
                      std::max(std::abs(box.lo.y - eye.y), std::abs(box.hi.y - eye.y)),
                      std::max(std::abs(box.lo.z - eye.z), std::abs(box.hi.z - eye.z))};
  auto least = [&](Vec3 n) {
    const Vec3 corner{n.x >= 0 ? box.lo.x : box.hi.x, n.y >= 0 ? box.lo.y : box.hi.y, n.z >= 0 ? box.lo.z : box.hi.z};
    return dot(n, corner - eye);
  };
  auto magnitude = [&](Vec3 n) { return std::abs(n.x) * far_side.x + std::abs(n.y) * far_side.y + std::abs(n.z) * far_side.z; };
  constexpr double kMargin = 1e-9;
  out.sides = true;
  for (int i = 0; i < 4; ++i) out.sides = out.sides && least(planes[i].n) > kMargin * magnitude(planes[i].n);
  // Ending at the point: distance (1 + kBeyondRelative) + kBeyondAbsolute <= far / along, where
  // along = depth / distance. With depth <= D (the box's largest depth) and distance >= r (its
  // least distance from the eye), far r / D >= r (1 + kBeyondRelative) + kBeyondAbsolute is
  // enough, and the margin covers the rounding of both sides.
  const Vec3 depth_n = planes[4].n;
  const double deepest = -least(depth_n * -1.0);
  const double nearest = distance_to_box(eye, box);
  out.before_far = out.sides && deepest > 0.0 && nearest > 0.0 &&
                   far_ * nearest / deepest * (1.0 - kMargin) > nearest * (1.0 + kBeyondRelative) + kBeyondAbsolute + kMargin * magnitude(depth_n);
  return out;
}

template <class Emit>
void ViewCone::each_ray_toward(const std::vector<Vec3>& points, const Box3* within, bool to_far, Emit&& emit) const {
  if (orthographic_) {
    PlannedRay ray{};
    for (std::size_t i = 0; i < points.size(); ++i)
      if (ortho_ray_toward(points[i], ray, to_far)) emit(i, ray.origin, ray.direction, ray.t_near, ray.t_far);
    return;
  }
  // ray_toward's arithmetic, operation for operation, in loops over a run of points: each loop's
  // iterations are independent, so the square roots and divisions of neighbouring points overlap
  // (and go two to an instruction), where one point at a time waits on each in turn.
  const Vec3 eye = transform_.eye();
  const bool omnidirectional = transform_.omnidirectional();
  const BoxSettles settled = within ? settles(*within) : BoxSettles{};
  const bool far_needed = to_far || !settled.before_far;
  const auto& planes = transform_.planes();
  const double near = transform_.near(), far = transform_.far();
  constexpr std::size_t kRun = 64;
  double squared[kRun], distance[kRun], inverse[kRun], along[kRun], t_near[kRun], t_far[kRun];
  bool inside[kRun];
  Vec3 direction[kRun];
  for (std::size_t start = 0; start < points.size(); start += kRun) {
    const std::size_t m = std::min(kRun, points.size() - start);
    const Vec3* p = points.data() + start;
    // The kept samples of a walk's candidates outgrow the caches, so the next run's points are
    // asked for while this run's are worked on.
    const Vec3* ahead = p + kRun;
    const Vec3* stop = points.data() + points.size();
    for (std::size_t line = 0; line < kRun * sizeof(Vec3); line += 64)
      if (reinterpret_cast<const char*>(ahead) + line < reinterpret_cast<const char*>(stop)) __builtin_prefetch(reinterpret_cast<const char*>(ahead) + line);
    for (std::size_t i = 0; i < m; ++i) squared[i] = dot(p[i] - eye, p[i] - eye);
    sqrt_run(squared, distance, m);
    divide_run(1.0, distance, inverse, m);
    for (std::size_t i = 0; i < m; ++i) direction[i] = (p[i] - eye) * inverse[i];
    if (omnidirectional) {
      for (std::size_t i = 0; i < m; ++i) inside[i] = true, t_near[i] = 0.0, t_far[i] = far;
    } else {
      if (settled.sides) {
        for (std::size_t i = 0; i < m; ++i) along[i] = dot(planes[4].n, direction[i]), inside[i] = along[i] > 0.0;
      } else {
        for (std::size_t i = 0; i < m; ++i) {
          const Vec3 d = direction[i];
          along[i] = dot(planes[4].n, d);
          // Bitwise on purpose (no branch per plane); as ints, which clang asks for.
          inside[i] = (int(!(dot(planes[0].n, d) < 0.0)) & int(!(dot(planes[1].n, d) < 0.0)) &
                       int(!(dot(planes[2].n, d) < 0.0)) & int(!(dot(planes[3].n, d) < 0.0)) & int(along[i] > 0.0)) != 0;
        }
      }
      divide_run(near, along, t_near, m);
      if (far_needed)
        divide_run(far, along, t_far, m);
      else
        for (std::size_t i = 0; i < m; ++i) t_far[i] = std::numeric_limits<double>::infinity();  // the point's end is the nearer
    }
    for (std::size_t i = 0; i < m; ++i) {
      if (!(distance[i] > 0.0) || !inside[i]) continue;
      const double t = to_far ? t_far[i] : std::min(t_far[i], distance[i] * (1.0 + kBeyondRelative) + kBeyondAbsolute);
      if (!(t > t_near[i])) continue;
      emit(start + i, eye, direction[i], t_near[i], t);
    }
  }
}

void ViewCone::rays_toward(const std::vector<Vec3>& points, const PlannedRay& prototype, std::vector<PlannedRay>& out,
                           const Box3* within, bool to_far) const {
  each_ray_toward(points, within, to_far, [&](std::size_t i, Vec3 origin, Vec3 direction, double t_near, double t_far) {
    PlannedRay& r = out.emplace_back(prototype);
    r.origin = origin, r.direction = direction, r.t_near = t_near, r.t_far = t_far, r.target = points[i];
  });
}

void ViewCone::cast_rays_toward(const std::vector<Vec3>& points, Vec3 mesh_origin, std::vector<RayLog::Ray>& cast,
                                std::vector<std::uint32_t>& aim, const Box3* within, bool to_far) const {
  // Written through pointers into slots made first, then the slots left over cut off: a
  // push_back per ray (its capacity check, out of line) cost as much as the arithmetic.
  const std::size_t before = cast.size();
  cast.resize(before + points.size());
  aim.resize(before + points.size());
  RayLog::Ray* next_ray = cast.data() + before;
  std::uint32_t* next_aim = aim.data() + before;
  each_ray_toward(points, within, to_far, [&](std::size_t i, Vec3 origin, Vec3 direction, double t_near, double t_far) {
    *next_ray++ = to_float(origin - mesh_origin, direction, t_near, t_far);
    *next_aim++ = std::uint32_t(i);
  });
  cast.resize(std::size_t(next_ray - cast.data()));
  aim.resize(cast.size());
}

RayPlan::RayPlan(const Scene& scene, const TriangleMesh& mesh, const Camera& camera, const SamplingOptions& options,
                 SampleCache* cache)
    : scene_(scene), mesh_(mesh), camera_(camera), options_(options), cone_(camera) {
  if (cache) cache_.emplace(cache->at(options));
  const int n = options.frustum_resolution;
  if (n <= 0) return;
  if (camera.omnidirectional()) {
    columns_ = 2 * n, rows_ = n;  // equal-area cells: uniform in azimuth and in sin(elevation)
  } else {
    // Square cells on the image plane (or the orthographic rectangle), at most 4N rows however
    // tall the field of view.
    const double aspect = camera.orthographic() ? camera.ortho_height / camera.ortho_width
                                                : std::tan(camera.vfov / 2) / std::tan(camera.hfov / 2);
    columns_ = n;
    rows_ = int(std::clamp(std::lround(n * aspect), 1L, 4L * n));
  }
}

std::size_t RayPlan::object_rays(std::uint32_t index, UnitRays& out, PlanTally& tally, SurfaceSamples& samples) const {
  out.clear();
  out.object = index;
  const bool building = index < scene_.buildings.size();
  const Box3& bounds = building ? scene_.buildings[index].bounds : scene_.meshes[index - scene_.buildings.size()].bounds;
  if (!cone_.transform().may_meet(bounds)) return 0;
  ++tally.candidates;
  const SurfaceSamples* kept = &samples;
  if (cache_)
    kept = &cache_->samples(index, samples);
  else
    sample_object(scene_, mesh_, index, options_, samples);
  tally.capped += kept->capped ? 1 : 0;
  out.surface = &kept->points;
  cone_.cast_rays_toward(kept->points, mesh_.origin, out.cast, out.aim, &bounds);
  out.surface_rays = out.size();
  if (options_.graze_offset > 0.0) {
    // The points passed just beside every silhouette edge, then their rays planned as one run.
    if (building) plan_grazing(index, out.grazing);
    else plan_mesh_grazing(index, out.grazing);
    cone_.cast_rays_toward(out.grazing, mesh_.origin, out.cast, out.aim, nullptr, /*to_far=*/true);
    tally.grazing += out.size() - out.surface_rays;
  }
  return out.surface_rays;
}

PlannedRay RayPlan::planned(const UnitRays& unit, std::size_t k) const {
  PlannedRay ray{};
  if (unit.object == kNoObjectIndex) {
    const std::size_t cell = unit.first_cell + unit.aim[k];
    SplitMix64 rng = SplitMix64::at(options_.seed, 2 * std::uint64_t(cell));
    plan_cell(cell, rng, ray);
    return ray;
  }
  const bool grazing = k >= unit.surface_rays;
  ray.aimed_at = unit.object;
  ray.source = grazing ? RaySource::grazing : RaySource::surface_sample;
  cone_.ray_toward(grazing ? unit.grazing[unit.aim[k]] : (*unit.surface)[unit.aim[k]], ray, /*to_far=*/grazing);
  return ray;
}

std::size_t RayPlan::object_rays(std::uint32_t index, std::vector<PlannedRay>& out, PlanTally& tally, SurfaceSamples& samples) const {
  UnitRays unit;
  const std::size_t surface = object_rays(index, unit, tally, samples);
  for (std::size_t k = 0; k < unit.size(); ++k) out.push_back(planned(unit, k));
  return surface;
}

void RayPlan::cell_rays(std::size_t first, std::size_t last, std::vector<PlannedRay>& out) const {
  UnitRays unit;
  cell_rays(first, last, unit);
  for (std::size_t k = 0; k < unit.size(); ++k) out.push_back(planned(unit, k));
}

// The points just either side of a silhouette edge p0-p1, sampled along it, that grazing rays
// aim at: the slivers where a float rounding error would show or hide what lies behind the edge.
void RayPlan::graze_along(Vec3 p0, Vec3 p1, std::vector<Vec3>& aims) const {
  const ViewTransform& view = cone_.transform();
  const bool ortho = view.orthographic();
  const Vec3 eye = view.eye(), forward = view.forward();
  const double ortho_size = ortho ? std::max(camera_.ortho_width, camera_.ortho_height) : 0.0;
  const Vec3 edge = p1 - p0;
  const double len = length(edge);
  if (!(len > 0.0)) return;
  const double steps = std::ceil(len / options_.spacing_m);
  const std::size_t m = std::max<std::size_t>(std::size_t(options_.edge_samples), steps > 1e6 ? std::size_t(1e6) : std::size_t(steps));
  for (std::size_t i = 0; i <= m; ++i) {
    const Vec3 p = p0 + edge * (double(i) / double(m));
    const Vec3 view_dir = ortho ? forward : p - eye;
    const Vec3 side = cross(view_dir, edge);
    const double side_len = length(side);
    if (!(side_len > 1e-12 * length(view_dir) * len)) continue;  // the edge seen end-on: no sliver
    const double reach = ortho ? ortho_size : length(view_dir);
    const double offset = std::max(options_.graze_offset * reach, kGrazeFloorRelative * length(p - mesh_.origin));
    for (double sign : {-1.0, 1.0}) aims.push_back(p + side * (sign * offset / side_len));
  }
}

// A building's silhouette: its vertical edges between a wall the eye sees and one it does not,
// and its roof edges between the roof and a wall on the other side of the eye's view.
void RayPlan::plan_grazing(std::uint32_t index, std::vector<Vec3>& aims) const {
  const Building& b = scene_.buildings[index];
  const ViewTransform& view = cone_.transform();
  const bool ortho = view.orthographic();
  const Vec3 eye = view.eye(), forward = view.forward();
  const std::vector<Vec2>& ring = b.footprint;
  const std::size_t n = ring.size();
  // Facing of wall k (footprint edge k -> k+1, counter-clockwise, so its outward normal is the
  // edge turned clockwise) and of the roof, from the eye (or against the view direction).
  std::vector<int> wall(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 a = ring[k], e = ring[(k + 1) % n] - a;
    const Vec2 outward{e.y, -e.x};
    wall[k] = facing(ortho ? -dot(outward, plan(forward)) : dot(outward, plan(eye) - a));
  }
  const int roof = facing(ortho ? -forward.z : eye.z - b.height);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 v = ring[k], next = ring[(k + 1) % n];
    if (silhouette(wall[(k + n - 1) % n], wall[k])) graze_along({v.x, v.y, 0.0}, {v.x, v.y, b.height}, aims);
    if (silhouette(wall[k], roof)) graze_along({v.x, v.y, b.height}, {next.x, next.y, b.height}, aims);
  }
}

// A mesh object's silhouette: its boundary edges, and the edges whose triangles do not all face
// the eye the same way (or one is seen edge-on). Triangles are two-sided, so a facing is a side
// of the triangle's plane, whichever way its vertices wind.
void RayPlan::plan_mesh_grazing(std::uint32_t index, std::vector<Vec3>& aims) const {
  const std::size_t k = index - scene_.buildings.size();
  const MeshObject& m = scene_.meshes[k];
  const ViewTransform& view = cone_.transform();
  const bool ortho = view.orthographic();
  const Vec3 eye = view.eye(), forward = view.forward();
  auto facing_of = [&](std::uint32_t t) {
    const Vec3 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    const Vec3 normal = cross(b - a, c - a);
    return facing(ortho ? -dot(normal, forward) : dot(normal, eye - a));
  };
  for (const MeshEdge& e : mesh_.mesh_edges[k]) {
    bool rim = e.triangles.size() == 1;
    const int first = facing_of(e.triangles[0]);
    for (std::size_t i = 1; i < e.triangles.size() && !rim; ++i) rim = silhouette(first, facing_of(e.triangles[i]));
    if (rim || first == 0) graze_along(e.a, e.b, aims);
  }
}

bool RayPlan::plan_cell(std::size_t cell, SplitMix64& rng, PlannedRay& ray) const {
  const int i = int(cell % std::size_t(columns_)), j = int(cell / std::size_t(columns_));
  const double r1 = rng.unit(), r2 = rng.unit();
  const ViewTransform& view = cone_.transform();
  ray = PlannedRay{};
  ray.origin = camera_.position;
  ray.aimed_at = kNoObjectIndex;
  ray.source = RaySource::stratified;
  // Cell (i, j) of the grid over normalised device coordinates [-1, 1]^2, jittered.
  const double u = -1.0 + (i + r1) * 2.0 / columns_, v = -1.0 + (j + r2) * 2.0 / rows_;
  if (camera_.orthographic()) {
    ray.origin = view.near_point_at(u, v);  // one parallel ray per cell of the view box
    ray.direction = view.forward();
  } else if (camera_.omnidirectional()) {
    const double azimuth = (i + r1) * kTwoPi / columns_;
    const double z = -1.0 + (j + r2) * 2.0 / rows_;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    ray.direction = {r * std::cos(azimuth), r * std::sin(azimuth), z};
  } else {
    ray.direction = view.direction_through(u, v);
  }
  if (!cone_.extent(ray.direction, ray.t_near, ray.t_far) || !(ray.t_far > ray.t_near)) return false;
  ray.target = ray.origin + ray.direction * ray.t_far;
  return true;
}

void RayPlan::cell_rays(std::size_t first, std::size_t last, UnitRays& out) const {
  out.clear();
  out.first_cell = first;
  SplitMix64 rng = SplitMix64::at(options_.seed, 2 * std::uint64_t(first));
  PlannedRay ray{};
  for (std::size_t c = first; c < last && c < cells(); ++c)
    if (plan_cell(c, rng, ray)) {
      out.cast.push_back(to_float(ray.origin - mesh_.origin, ray.direction, ray.t_near, ray.t_far));
      out.aim.push_back(std::uint32_t(c - first));
    }
}

}  // namespace cullcheck::oracle
