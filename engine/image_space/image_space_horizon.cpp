#include "engine/image_space/image_space_horizon.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/elapsed.hpp"
#include "engine/horizon/polar_geometry.hpp"

namespace cullcheck {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Points shallower than this are never projected, so 1/depth stays finite even with near = 0.
// A micrometre: nothing modelled is that thin.
constexpr double kMinDepth = 1e-6;

double widened(double v, double direction, double rounding) {
  return v + direction * screen_slack(rounding) * (1.0 + std::abs(v));
}

// A projected point and its coordinate rounding over depth (screen_slack).
struct ScreenPoint {
  Vec2 screen;
  double rounding;
};

// The projected extent of a set of points: their screen-x range, highest screen y and largest
// rounding. An empty extent has x_min > x_max, which hides nothing (ViewPlaneHorizon).
struct ScreenExtent {
  double x_min = kInfinity, x_max = -kInfinity, y_max = -kInfinity, rounding = 0.0;
  void add(const ScreenPoint& p) {
    x_min = std::min(x_min, p.screen.x);
    x_max = std::max(x_max, p.screen.x);
    y_max = std::max(y_max, p.screen.y);
    rounding = std::max(rounding, p.rounding);
  }
};

double magnitude(Vec3 p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}); }

class ViewPlane {
 public:
  explicit ViewPlane(const Camera& camera) : eye_(camera.position), basis_(basis_of(camera)) {}

  // Screen (x, y) of p, or nothing when p is not deeper than min_depth.
  std::optional<ScreenPoint> project(Vec3 p, double min_depth) const {
    const Vec3 d = p - eye_;
    const double depth = dot(basis_.forward, d);
    if (!(depth > min_depth)) return std::nullopt;
    return ScreenPoint{{dot(basis_.right, d) / depth, dot(basis_.up, d) / depth}, std::max(eye_magnitude_, magnitude(p)) / depth};
  }

  // Extent of a ground-standing box (8 corners): nothing if a corner is not deeper than min_depth.
  std::optional<ScreenExtent> box(const Box2& plan_box, double top, double min_depth) const {
    ScreenExtent e;
    for (double x : {plan_box.lo.x, plan_box.hi.x})
      for (double y : {plan_box.lo.y, plan_box.hi.y})
        for (double z : {0.0, top}) {
          const auto screen = project({x, y, z}, min_depth);
          if (!screen) return std::nullopt;
          e.add(*screen);
        }
    return e;
  }

  // Extent of a CVP (its 2n corners), likewise.
  std::optional<ScreenExtent> prism(const ConvexVerticalPrism& prism, double min_depth) const {
    ScreenExtent e;
    for (Vec2 v : prism.ring)
      for (double z : {0.0, prism.height}) {
        const auto screen = project({v.x, v.y, z}, min_depth);
        if (!screen) return std::nullopt;
        e.add(*screen);
      }
    return e;
  }

  // The published shadow of a CVP: its x range, and the smaller projected top y of the two
  // extreme-x vertices (ties in x: the lower top). Nothing when a corner is shallower than
  // min_depth (the near plane: clipped geometry hides nothing).
  struct Shadow {
    double x_min, x_max, y, rounding;
  };
  std::optional<Shadow> shadow(const ConvexVerticalPrism& prism, double min_depth) const {
    double x_min = kInfinity, x_max = -kInfinity, y_at_min = kInfinity, y_at_max = kInfinity, rounding = 0.0;
    for (Vec2 v : prism.ring) {
      const auto bottom = project({v.x, v.y, 0.0}, min_depth), top = project({v.x, v.y, prism.height}, min_depth);
      if (!bottom || !top) return std::nullopt;
      rounding = std::max({rounding, bottom->rounding, top->rounding});
      // With pitch or roll a vertical edge leans on the screen, and its bottom may be the
      // extreme; the naive port still takes that vertex's top as the height.
      for (double x : {bottom->screen.x, top->screen.x}) {
        if (x < x_min || (x == x_min && top->screen.y < y_at_min)) x_min = x, y_at_min = top->screen.y;
        if (x > x_max || (x == x_max && top->screen.y < y_at_max)) x_max = x, y_at_max = top->screen.y;
      }
    }
    return Shadow{x_min, x_max, std::min(y_at_min, y_at_max), rounding};
  }

 private:
  Vec3 eye_;
  double eye_magnitude_ = magnitude(eye_);
  CameraBasis basis_;
};

// Front-to-back sweep entries, ordered as tuples: (nearest plan distance, is building, index);
// shadows waiting for the sweep: (farthest plan distance, insertion order, shadow).
using SweepEntry = std::tuple<double, bool, std::uint32_t>;
using WaitingShadow = std::tuple<double, std::uint64_t, double, double, double, double>;
template <class T>
using EarliestFirst = std::priority_queue<T, std::vector<T>, std::greater<T>>;

}  // namespace

// --- ViewPlaneHorizon ---------------------------------------------------------------------------

ViewPlaneHorizon::ViewPlaneHorizon(std::uint32_t bins) : horizon_(bins) {
  if (bins < 4) throw std::invalid_argument("oh_is needs at least 4 horizon bins (2 margins), got " + std::to_string(bins));
}

double ViewPlaneHorizon::to_bin_coordinate(double x) const {
  const double w = horizon_.bin_width();
  const double u = w + (x + half_width_) / (2.0 * half_width_) * (kTwoPi - 2.0 * w);
  return std::clamp(u, 0.5 * w, kTwoPi - 0.5 * w);
}

std::uint32_t ViewPlaneHorizon::bin_of(double x) const {
  if (std::isnan(x)) throw std::invalid_argument("oh_is: screen x is NaN, which lies in no bin");
  const double last = horizon_.bins() - 1;
  // The screen is closed: its edges belong to its outermost bins, not to the margins.
  const bool on_screen = std::abs(x) <= half_width_;
  const double bin = std::floor(to_bin_coordinate(x) / horizon_.bin_width());
  return static_cast<std::uint32_t>(on_screen ? std::clamp(bin, 1.0, last - 1) : std::clamp(bin, 0.0, last));
}

void ViewPlaneHorizon::reset(double half_width) {
  half_width_ = half_width;
  horizon_.reset();
  // Inset by half a bin so that exactly the two margin bins lie wholly outside.
  const double w = horizon_.bin_width();
  horizon_.restrict_to({1.5 * w, kTwoPi - 1.5 * w});
}

void ViewPlaneHorizon::raise(double x_min, double x_max, double y, double rounding) {
  if (!std::isfinite(y) || std::isnan(rounding)) return;
  const double a = widened(x_min, +1.0, rounding), b = widened(x_max, -1.0, rounding);
  if (!(a < b)) return;  // also NaN: raise nothing
  horizon_.raise({to_bin_coordinate(a), to_bin_coordinate(b)}, widened(y, -1.0, rounding));
}

double ViewPlaneHorizon::min_over(double x_min, double x_max, double rounding) {
  const double a = widened(x_min, -1.0, rounding), b = widened(x_max, +1.0, rounding);
  // NaN (in a value or the rounding) or an inverted range: nothing is read, nothing proven.
  if (!(a <= b)) return -kInfinity;
  return horizon_.min_over({to_bin_coordinate(a), to_bin_coordinate(b)});
}

// The shadows' heights are lowered by the full slack; the tested height is raised by its own
// coordinate rounding.
bool ViewPlaneHorizon::hides(double x_min, double x_max, double y_max, double rounding) {
  const double y = y_max + (screen_slack(rounding) - kScreenSlack) * (1.0 + std::abs(y_max));
  return std::isfinite(y) && y < min_over(x_min, x_max, rounding);
}

// --- ImageSpaceHorizonCulling ------------------------------------------------------------------

ImageSpaceHorizonCulling::ImageSpaceHorizonCulling(const Scene& scene, const MethodOptions& options)
    : scene_(scene), quadtree_(scene, options.quadtree_leaf_size), horizon_(options.horizon_bins) {}

bool ImageSpaceHorizonCulling::claims_conservative_for(const Camera& camera) const {
  return camera.omnidirectional() || (camera.pitch == 0.0 && camera.roll == 0.0);
}

CullResult ImageSpaceHorizonCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  CullStatistics& stats = result.stats;
  const ViewVolume volume(camera);
  const ViewPlane view(camera);
  // No view plane in 360-degree mode: the sweep below then tests the view volume only.
  const bool occlusion = !camera.omnidirectional();
  // A box with a corner at or in front of the near plane is never culled by the horizon; a CVP
  // with a vertex in front of it is never an occluder.
  const double min_depth = std::max(camera.near, kMinDepth);
  if (occlusion) horizon_.reset(std::tan(camera.hfov / 2));
  horizon_.take_node_visits();
  const Vec2 e = plan(camera.position);

  auto hidden = [&](const Box2& plan_box, double top) {
    if (!occlusion) return false;
    const auto extent = view.box(plan_box, top, min_depth);
    return extent && horizon_.hides(extent->x_min, extent->x_max, extent->y_max, extent->rounding);
  };

  EarliestFirst<SweepEntry> sweep;
  EarliestFirst<WaitingShadow> waiting;
  std::uint64_t shadow_order = 0;
  const auto& cells = quadtree_.cells();
  const auto& order = quadtree_.buildings();
  if (!cells.empty() && cells[0].last > cells[0].first) sweep.emplace(min_distance(e, cells[0].bounds), false, 0u);

  while (!sweep.empty()) {
    const auto [distance, is_building, index] = sweep.top();
    sweep.pop();
    // Merge every shadow whose prism lies wholly nearer (in plan) than this entry.
    while (!waiting.empty() && std::get<0>(waiting.top()) < distance) {
      const auto& [farthest, n, x_min, x_max, y, rounding] = waiting.top();
      horizon_.raise(x_min, x_max, y, rounding);
      ++stats.occluders_applied;
      waiting.pop();
    }
    if (!is_building) {
      const Quadtree::Cell& cell = cells[index];
      ++stats.cells_tested;
      const Box3 box{{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}};
      // Both boxes of the cell's height split (Quadtree::Cell), as OH(OS)'s cell_hidden: every
      // building lies in one of them, and each is as sharp a proof as the one box.
      if (!volume.may_intersect(box) ||
          (hidden(cell.tall_bounds, cell.max_height) && (!cell.has_rest() || hidden(cell.bounds, cell.rest_height))))
        continue;
      if (cell.leaf()) {
        for (std::uint32_t i = cell.first; i < cell.last; ++i)
          sweep.emplace(min_distance(e, scene_.buildings[order[i]].bounds.plan()), true, order[i]);
      } else {
        for (std::uint32_t c = cell.first_child; c < cell.first_child + 4; ++c)
          if (cells[c].last > cells[c].first) sweep.emplace(min_distance(e, cells[c].bounds), false, c);
      }
      continue;
    }
    const Building& building = scene_.buildings[index];
    ++stats.buildings_tested;
    if (!volume.may_intersect(building.bounds) || hidden(building.bounds.plan(), building.height)) continue;
    // The box may show; the building is hidden only if every CVP is.
    const bool visible = !occlusion || std::any_of(building.prisms.begin(), building.prisms.end(), [&](const auto& prism) {
                           const auto extent = view.prism(prism, min_depth);
                           return !extent || !horizon_.hides(extent->x_min, extent->x_max, extent->y_max, extent->rounding);
                         });
    if (!visible) continue;
    result.pvs.push_back(building.id);
    if (!occlusion) continue;
    for (const ConvexVerticalPrism& prism : building.prisms)
      if (const auto s = view.shadow(prism, min_depth))
        waiting.emplace(max_vertex_distance(prism.ring, e), shadow_order++, s->x_min, s->x_max, s->y, s->rounding);
  }
  std::sort(result.pvs.begin(), result.pvs.end());
  stats.horizon_nodes = horizon_.take_node_visits();
  stats.cull_ms = ms_since(start);
  return result;
}

}  // namespace cullcheck
