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

}  // namespace

ViewCone::ViewCone(const Camera& c)
    : volume_(c), basis_(basis_of(c)), eye_(c.position), near_(c.near), far_(c.far), orthographic_(c.orthographic()) {
  if (orthographic_) half_width_ = c.ortho_width / 2, half_height_ = c.ortho_height / 2;
}

bool ViewCone::extent(Vec3 d, double& t_near, double& t_far) const {
  if (orthographic_) {
    if (!(d == basis_.forward)) return false;
    t_near = 0.0, t_far = far_ - near_;
    return true;
  }
  if (volume_.omnidirectional) {
    t_near = 0.0, t_far = far_;
    return true;
  }
  for (int i = 0; i < 4; ++i)  // the side planes pass through the eye: a test on directions
    if (dot(volume_.planes[i].n, d) < 0.0) return false;
  const double along = dot(basis_.forward, d);
  if (!(along > 0.0)) return false;
  t_near = near_ / along, t_far = far_ / along;
  return true;
}

bool ViewCone::ray_toward(Vec3 p, PlannedRay& out) const {
  if (orthographic_) {
    const Vec3 to = p - eye_;
    if (std::abs(dot(to, basis_.right)) > half_width_ || std::abs(dot(to, basis_.up)) > half_height_) return false;
    const double depth = dot(to, basis_.forward) - near_;  // from the near plane
    if (!(depth >= 0.0)) return false;                      // before the near plane: clipped
    out.origin = p - basis_.forward * depth;
    out.direction = basis_.forward;
    out.t_near = 0.0;
    out.t_far = std::min(far_ - near_, depth * (1.0 + kBeyondRelative) + kBeyondAbsolute);
  } else {
    const Vec3 to = p - eye_;
    const double distance = length(to);
    if (!(distance > 0.0)) return false;
    out.origin = eye_;
    out.direction = to * (1.0 / distance);
    if (!extent(out.direction, out.t_near, out.t_far)) return false;
    out.t_far = std::min(out.t_far, distance * (1.0 + kBeyondRelative) + kBeyondAbsolute);
  }
  out.target = p;
  return out.t_far > out.t_near;
}

RayPlan::RayPlan(const Scene& scene, const Camera& camera, const SamplingOptions& options)
    : scene_(scene), camera_(camera), options_(options), cone_(camera), basis_(basis_of(camera)), rng_(options.seed) {
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

void RayPlan::plan_object(std::uint32_t index, std::vector<PlannedRay>& out) {
  const bool building = index < scene_.buildings.size();
  const Box3& bounds = building ? scene_.buildings[index].bounds : scene_.meshes[index - scene_.buildings.size()].bounds;
  if (!cone_.volume().may_intersect(bounds)) return;
  ++candidates_;
  const SurfaceSamples samples = building ? surface_samples(scene_.buildings[index], options_)
                                          : surface_samples(scene_.meshes[index - scene_.buildings.size()], options_);
  capped_ += samples.capped ? 1 : 0;
  PlannedRay ray{};
  ray.aimed_at = index;
  ray.source = RaySource::surface_sample;
  for (Vec3 p : samples.points)
    if (cone_.ray_toward(p, ray)) out.push_back(ray);
}

void RayPlan::plan_cell(std::vector<PlannedRay>& out) {
  const int i = int(cell_ % std::size_t(columns_)), j = int(cell_ / std::size_t(columns_));
  ++cell_;
  const double r1 = rng_.unit(), r2 = rng_.unit();
  PlannedRay ray{};
  ray.origin = camera_.position;
  ray.aimed_at = kNoObjectIndex;
  ray.source = RaySource::stratified;
  if (camera_.orthographic()) {
    // The rectangle [-W/2, W/2] x [-H/2, H/2] on the near plane, one parallel ray per cell.
    const double u = -camera_.ortho_width / 2 + (i + r1) * camera_.ortho_width / columns_;
    const double v = -camera_.ortho_height / 2 + (j + r2) * camera_.ortho_height / rows_;
    ray.origin = camera_.position + basis_.right * u + basis_.up * v + basis_.forward * camera_.near;
    ray.direction = basis_.forward;
  } else if (camera_.omnidirectional()) {
    const double azimuth = (i + r1) * kTwoPi / columns_;
    const double z = -1.0 + (j + r2) * 2.0 / rows_;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    ray.direction = {r * std::cos(azimuth), r * std::sin(azimuth), z};
  } else {
    // The image plane at distance 1: [-U, U] x [-V, V] maps exactly onto the four side planes.
    const double U = std::tan(camera_.hfov / 2), V = std::tan(camera_.vfov / 2);
    const double u = -U + (i + r1) * 2 * U / columns_;
    const double v = -V + (j + r2) * 2 * V / rows_;
    ray.direction = normalized(basis_.forward + basis_.right * u + basis_.up * v);
  }
  if (cone_.extent(ray.direction, ray.t_near, ray.t_far) && ray.t_far > ray.t_near) {
    ray.target = ray.origin + ray.direction * ray.t_far;
    out.push_back(ray);
  }
}

bool RayPlan::next(std::vector<PlannedRay>& out, std::size_t count) {
  const std::size_t before = out.size();
  const std::size_t cells = std::size_t(columns_) * std::size_t(rows_);
  const std::size_t objects = scene_.object_count();
  while (out.size() < count && object_ < objects) plan_object(object_++, out);
  while (out.size() < count && cell_ < cells) plan_cell(out);
  return out.size() > before || object_ < objects || cell_ < cells;
}

}  // namespace cullcheck::oracle
