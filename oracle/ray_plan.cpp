#include "oracle/ray_plan.hpp"

#include <algorithm>
#include <cmath>

#include "oracle/surface_samples.hpp"

namespace cullcheck::oracle {
namespace {

// A surface ray ends this far beyond its sample point (relative, plus absolute metres): far
// enough that float rounding cannot make it stop short of the sample's face, near enough that
// a ray grazing past the sample's edge does not go on to witness what lies behind it.
constexpr double kBeyondRelative = 1e-5;
constexpr double kBeyondAbsolute = 1e-5;

// The graze distance's floor relative to a point's distance from the mesh origin: 1e-6 is about
// 16 float ulps (2^-24 ~ 6e-8), so Embree sees the ray on the intended side of the edge.
constexpr double kGrazeFloorRelative = 1e-6;

// Which way a face looks, as the eye sees it: +1 toward the eye, -1 away, 0 edge-on.
int facing(double toward_eye) { return toward_eye > 0.0 ? 1 : toward_eye < 0.0 ? -1 : 0; }
bool silhouette(int a, int b) { return a == 0 || b == 0 || a != b; }

}  // namespace

ViewCone::ViewCone(const Camera& c)
    : transform_(c), forward_(transform_.forward()), near_(c.near), far_(c.far), orthographic_(c.orthographic()) {}

bool ViewCone::extent(Vec3 d, double& t_near, double& t_far) const {
  if (orthographic_) {
    if (!(d == forward_)) return false;
    t_near = 0.0, t_far = far_ - near_;
    return true;
  }
  return transform_.extent(d, t_near, t_far);
}

bool ViewCone::ray_toward(Vec3 p, PlannedRay& out, bool to_far) const {
  if (orthographic_) {
    const Clip c = transform_.clip(p);  // w = 1: x and y are the view box's normalised coordinates
    if (std::abs(c.x) > 1.0 || std::abs(c.y) > 1.0) return false;
    const double depth = c.z - near_;  // from the near plane
    if (!(depth >= 0.0)) return false;  // before the near plane: clipped
    out.origin = p - forward_ * depth;
    out.direction = forward_;
    out.t_near = 0.0;
    out.t_far = far_ - near_;
    if (!to_far) out.t_far = std::min(out.t_far, depth * (1.0 + kBeyondRelative) + kBeyondAbsolute);
  } else {
    const Vec3 to = p - transform_.eye();
    const double distance = length(to);
    if (!(distance > 0.0)) return false;
    out.origin = transform_.eye();
    out.direction = to * (1.0 / distance);
    if (!extent(out.direction, out.t_near, out.t_far)) return false;
    if (!to_far) out.t_far = std::min(out.t_far, distance * (1.0 + kBeyondRelative) + kBeyondAbsolute);
  }
  out.target = p;
  return out.t_far > out.t_near;
}

RayPlan::RayPlan(const Scene& scene, const TriangleMesh& mesh, const Camera& camera, const SamplingOptions& options)
    : scene_(scene), mesh_(mesh), camera_(camera), options_(options), cone_(camera) {
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

std::size_t RayPlan::object_rays(std::uint32_t index, std::vector<PlannedRay>& out, PlanTally& tally,
                                 SurfaceSamples& samples) const {
  const bool building = index < scene_.buildings.size();
  const Box3& bounds = building ? scene_.buildings[index].bounds : scene_.meshes[index - scene_.buildings.size()].bounds;
  if (!cone_.transform().may_meet(bounds)) return 0;
  ++tally.candidates;
  if (building)
    surface_samples(scene_.buildings[index], mesh_.roofs[index], options_, samples);
  else
    surface_samples(scene_.meshes[index - scene_.buildings.size()], options_, samples);
  tally.capped += samples.capped ? 1 : 0;
  PlannedRay ray{};
  ray.aimed_at = index;
  ray.source = RaySource::surface_sample;
  const std::size_t before = out.size();
  for (Vec3 p : samples.points)
    if (cone_.ray_toward(p, ray)) out.push_back(ray);
  const std::size_t surface = out.size() - before;
  if (options_.graze_offset > 0.0) {
    if (building) plan_grazing(index, out, tally);
    else plan_mesh_grazing(index, out, tally);
  }
  return surface;
}

// Rays just either side of a silhouette edge p0-p1 of object `index`, sampled along it: the
// slivers where a float rounding error would show or hide what lies behind the edge.
void RayPlan::graze_along(std::uint32_t index, Vec3 p0, Vec3 p1, std::vector<PlannedRay>& out, PlanTally& tally) const {
  const ViewTransform& view = cone_.transform();
  const bool ortho = view.orthographic();
  const Vec3 eye = view.eye(), forward = view.forward();
  const double ortho_size = ortho ? std::max(camera_.ortho_width, camera_.ortho_height) : 0.0;
  PlannedRay ray{};
  ray.aimed_at = index;
  ray.source = RaySource::grazing;
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
    for (double sign : {-1.0, 1.0})
      if (cone_.ray_toward(p + side * (sign * offset / side_len), ray, /*to_far=*/true)) {
        out.push_back(ray);
        ++tally.grazing;
      }
  }
}

// A building's silhouette: its vertical edges between a wall the eye sees and one it does not,
// and its roof edges between the roof and a wall on the other side of the eye's view.
void RayPlan::plan_grazing(std::uint32_t index, std::vector<PlannedRay>& out, PlanTally& tally) const {
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
    if (silhouette(wall[(k + n - 1) % n], wall[k])) graze_along(index, {v.x, v.y, 0.0}, {v.x, v.y, b.height}, out, tally);
    if (silhouette(wall[k], roof)) graze_along(index, {v.x, v.y, b.height}, {next.x, next.y, b.height}, out, tally);
  }
}

// A mesh object's silhouette: its boundary edges, and the edges whose triangles do not all face
// the eye the same way (or one is seen edge-on). Triangles are two-sided, so a facing is a side
// of the triangle's plane, whichever way its vertices wind.
void RayPlan::plan_mesh_grazing(std::uint32_t index, std::vector<PlannedRay>& out, PlanTally& tally) const {
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
    if (rim || first == 0) graze_along(index, e.a, e.b, out, tally);
  }
}

void RayPlan::plan_cell(std::size_t cell, SplitMix64& rng, std::vector<PlannedRay>& out) const {
  const int i = int(cell % std::size_t(columns_)), j = int(cell / std::size_t(columns_));
  const double r1 = rng.unit(), r2 = rng.unit();
  const ViewTransform& view = cone_.transform();
  PlannedRay ray{};
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
  if (cone_.extent(ray.direction, ray.t_near, ray.t_far) && ray.t_far > ray.t_near) {
    ray.target = ray.origin + ray.direction * ray.t_far;
    out.push_back(ray);
  }
}

void RayPlan::cell_rays(std::size_t first, std::size_t last, std::vector<PlannedRay>& out) const {
  SplitMix64 rng = SplitMix64::at(options_.seed, 2 * std::uint64_t(first));
  for (std::size_t c = first; c < last && c < cells(); ++c) plan_cell(c, rng, out);
}

}  // namespace cullcheck::oracle
