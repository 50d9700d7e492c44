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

ViewCone::ViewCone(const Camera& c) : volume_(c), forward_(basis_of(c).forward), near_(c.near), far_(c.far) {}

bool ViewCone::extent(Vec3 d, double& t_near, double& t_far) const {
  if (volume_.omnidirectional) {
    t_near = 0.0, t_far = far_;
    return true;
  }
  for (int i = 0; i < 4; ++i)  // the side planes pass through the eye: a test on directions
    if (dot(volume_.planes[i].n, d) < 0.0) return false;
  const double along = dot(forward_, d);
  if (!(along > 0.0)) return false;
  t_near = near_ / along, t_far = far_ / along;
  return true;
}

RayPlan::RayPlan(const Scene& scene, const Camera& camera, const SamplingOptions& options)
    : scene_(scene), camera_(camera), options_(options), cone_(camera), basis_(basis_of(camera)), rng_(options.seed) {
  const int n = options.frustum_resolution;
  if (n <= 0) return;
  if (camera.omnidirectional()) {
    columns_ = 2 * n, rows_ = n;  // equal-area cells: uniform in azimuth and in sin(elevation)
  } else {
    // Square cells on the image plane, at most 4N rows however tall the field of view.
    const double U = std::tan(camera.hfov / 2), V = std::tan(camera.vfov / 2);
    columns_ = n;
    rows_ = int(std::clamp(std::lround(n * V / U), 1L, 4L * n));
  }
}

void RayPlan::plan_building(std::uint32_t index, std::vector<PlannedRay>& out) {
  const Building& b = scene_.buildings[index];
  if (!cone_.volume().may_intersect(b.bounds)) return;
  ++candidates_;
  const SurfaceSamples samples = surface_samples(b, options_);
  capped_ += samples.capped ? 1 : 0;
  const Vec3 eye = camera_.position;
  for (Vec3 p : samples.points) {
    const Vec3 to = p - eye;
    const double distance = length(to);
    if (!(distance > 0.0)) continue;
    const Vec3 d = to * (1.0 / distance);
    double t_near, t_far;
    if (!cone_.extent(d, t_near, t_far)) continue;
    t_far = std::min(t_far, distance * (1.0 + kBeyondRelative) + kBeyondAbsolute);
    if (!(t_far > t_near)) continue;
    out.push_back({d, t_near, t_far, p, index, RaySource::surface_sample});
  }
}

void RayPlan::plan_cell(std::vector<PlannedRay>& out) {
  const int i = int(cell_ % std::size_t(columns_)), j = int(cell_ / std::size_t(columns_));
  ++cell_;
  const double r1 = rng_.unit(), r2 = rng_.unit();
  Vec3 d;
  if (camera_.omnidirectional()) {
    const double azimuth = (i + r1) * kTwoPi / columns_;
    const double z = -1.0 + (j + r2) * 2.0 / rows_;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    d = {r * std::cos(azimuth), r * std::sin(azimuth), z};
  } else {
    // The image plane at distance 1: [-U, U] x [-V, V] maps exactly onto the four side planes.
    const double U = std::tan(camera_.hfov / 2), V = std::tan(camera_.vfov / 2);
    const double u = -U + (i + r1) * 2 * U / columns_;
    const double v = -V + (j + r2) * 2 * V / rows_;
    d = normalized(basis_.forward + basis_.right * u + basis_.up * v);
  }
  double t_near, t_far;
  if (cone_.extent(d, t_near, t_far) && t_far > t_near)
    out.push_back({d, t_near, t_far, camera_.position + d * t_far, kNoBuilding, RaySource::stratified});
}

bool RayPlan::next(std::vector<PlannedRay>& out, std::size_t count) {
  const std::size_t before = out.size();
  const std::size_t cells = std::size_t(columns_) * std::size_t(rows_);
  while (out.size() < count && building_ < scene_.buildings.size()) plan_building(building_++, out);
  while (out.size() < count && cell_ < cells) plan_cell(out);
  return out.size() > before || building_ < scene_.buildings.size() || cell_ < cells;
}

}  // namespace cullcheck::oracle
