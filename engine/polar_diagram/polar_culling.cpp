#include "engine/polar_diagram/polar_culling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/elapsed.hpp"
#include "engine/polar_diagram/exact_sign.hpp"

namespace cullcheck {
namespace {

// Whether p lies inside or on a simple polygon, exactly: on an edge, or an odd number of edges
// cross the horizontal ray to its right (half-open in y, so vertices count once).
bool inside_or_on(const std::vector<Vec2>& ring, Vec2 p) {
  bool inside = false;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const Vec2 a = ring[i], b = ring[(i + 1) % n];
    const int turn = polar::orient(a, b, p);
    if (turn == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
        p.y <= std::max(a.y, b.y))
      return true;
    if ((a.y > p.y) != (b.y > p.y) && (b.y > a.y ? turn > 0 : turn < 0)) inside = !inside;
  }
  return inside;
}

double farthest(Vec2 p, const Box2& b) {
  const double dx = std::max(std::abs(b.lo.x - p.x), std::abs(b.hi.x - p.x));
  const double dy = std::max(std::abs(b.lo.y - p.y), std::abs(b.hi.y - p.y));
  return std::sqrt(dx * dx + dy * dy);
}

}  // namespace

PolarDiagramCulling::PolarDiagramCulling(const Scene& scene, polar::FanOptions options)
    : scene_(scene), fan_(scene, options) {
  lowest_ = scene.buildings.empty() ? 0.0 : HUGE_VAL;
  for (const Building& b : scene.buildings) lowest_ = std::min(lowest_, b.height), tallest_ = std::max(tallest_, b.height);
}

std::string PolarDiagramCulling::unsupported_camera(const Camera& camera) const {
  if (std::string why = CullingMethod::unsupported_camera(camera); !why.empty()) return why;
  if (!fan_.inside_frame(plan(camera.position)))
    return "polar_diagram: the eye lies outside the scene's frame (its bounds grown by a quarter)";
  return "";
}

std::string PolarDiagramCulling::plan_view_exact(const Camera& camera) const {
  if (camera.orthographic()) return "orthographic camera";
  if (!camera.omnidirectional() && (camera.pitch != 0.0 || camera.roll != 0.0)) return "camera not level";
  const double z = camera.position.z;
  if (!(lowest_ > z)) return "a building is not taller than the eye";
  const Vec2 eye = plan(camera.position);
  const double rise = camera.omnidirectional() ? HUGE_VAL : std::tan(camera.vfov / 2);
  if (!camera.omnidirectional() && !(camera.hfov < M_PI)) return "field of view of half a turn or more";
  for (const Building& b : scene_.buildings) {
    const Box2 box = b.bounds.plan();
    if (box.contains(eye) && inside_or_on(b.footprint, eye)) return "the eye lies inside or on a building";
    const double far = farthest(eye, box);
    if (std::hypot(far, std::max(b.height - z, z)) > camera.far) return "a building reaches beyond the far plane";
    if (!camera.omnidirectional() && min_distance(eye, box) * std::cos(camera.hfov / 2) < camera.near)
      return "a building may lie nearer than the near plane";
    if (b.height < tallest_ && !(b.height >= z + far * rise)) return "a building is low enough to be seen over";
  }
  return "";
}

CullResult PolarDiagramCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  polar::FanResult fan = fan_.visible(plan(camera.position), polar::plan_wedge(camera));
  CullResult result;
  result.pvs = std::move(fan.visible);
  result.stats.cells_tested = fan.stats.cells_walked;
  result.stats.buildings_tested = fan.stats.vertices_tested + fan.stats.edges_tested;
  last_ = fan.stats;
  result.stats.cull_ms = ms_since(start);
  return result;
}

}  // namespace cullcheck
