// Exact plan-view visibility with CGAL (the only translation unit of the oracle that includes
// CGAL). Why the plan view can be the 3D truth, under exact_2d_applies (conditions 1-4 in the
// header): take any ray in the view volume and let A be the first footprint its plan projection
// enters, at plan distance d. The ray cannot touch any building before d (walls stand on the
// footprint boundaries, roofs over their interiors). At d its height is z_eye + d tan(beta),
// with beta <= vfov / 2 for a level perspective camera. If that height is in [0, h_A] it hits
// A's wall; if below 0 it went under the ground and hits nothing; above h_A is impossible when
// A is the tallest (the ray would be rising and stays above every building) and excluded by
// condition 4 otherwise. So every first hit in 3D is the plan-first building in that azimuth;
// conversely the horizontal ray in an azimuth where A is plan-first hits A at eye height, inside
// the volume by conditions 1 and 3. Hence a building is seen through a set of directions of
// positive measure in 3D exactly when its plan-view angular extent inside the wedge is positive.
#include "oracle/exact_2d.hpp"

#include <CGAL/Arr_naive_point_location.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangular_expansion_visibility_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "oracle/view_transform.hpp"

namespace cullcheck::oracle {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;  // exact predicates and constructions
using Point = Kernel::Point_2;
using FT = Kernel::FT;
using Traits = CGAL::Arr_segment_traits_2<Kernel>;
using Arrangement = CGAL::Arrangement_2<Traits>;
using Visibility = CGAL::Triangular_expansion_visibility_2<Arrangement, CGAL::Tag_true>;  // regularized

struct ExactFootprint {
  ObjectId id;
  std::vector<Point> ring;
  Box2 box;
};

// The plan view's horizontal wedge as two exact half-planes n . (p - eye) >= 0 (the camera's
// right and left side planes, whose normals are horizontal for a level camera).
struct Wedge {
  bool everything = true;
  std::array<Kernel::Vector_2, 2> normals;
  Vec2 right_edge;  // direction of the wedge's clockwise edge, for measuring angles in double
};

Wedge wedge_of(const Camera& camera) {
  Wedge w;
  if (camera.omnidirectional()) return w;
  const ViewTransform view(camera);
  w.everything = false;
  // The left and right planes (w + x >= 0, w - x >= 0) pass through the eye; for a level camera
  // their normals are horizontal.
  for (int i = 0; i < 2; ++i) w.normals[i] = {view.planes()[i].n.x, view.planes()[i].n.y};
  const double a = camera.yaw - camera.hfov / 2;
  w.right_edge = {std::cos(a), std::sin(a)};
  return w;
}

// Clips [a, b] to the half-plane n . (p - eye) >= 0, exactly. False when nothing remains.
bool clip(Point& a, Point& b, const Point& eye, const Kernel::Vector_2& n) {
  const FT fa = n * (a - eye), fb = n * (b - eye);
  const bool ia = !CGAL::is_negative(fa), ib = !CGAL::is_negative(fb);
  if (!ia && !ib) return false;
  if (ia && ib) return true;
  const Point x = a + (b - a) * (fa / (fa - fb));
  (ia ? b : a) = x;
  return true;
}

std::vector<ExactFootprint> exact_footprints(const Scene& scene) {
  std::vector<ExactFootprint> out;
  for (const Building& b : scene.buildings) {
    ExactFootprint f{b.id, {}, b.bounds.plan()};
    for (Vec2 v : b.footprint) f.ring.emplace_back(v.x, v.y);
    out.push_back(std::move(f));
  }
  return out;
}

Vec2 to_vec2(const Point& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

bool on_segment(const Point& p, const Point& r, const Point& x) {
  return CGAL::collinear(p, r, x) && CGAL::collinear_are_ordered_along_line(p, x, r);
}

// An angular interval in radians, measured counter-clockwise from a reference direction.
struct Interval {
  double start, width;
};

VisibleExtent2d merge(std::vector<Interval> pieces, bool circular) {
  // The pieces of one building come from one star-shaped polygon, so they do not overlap; they
  // touch where consecutive polygon edges lie on the same building (1e-12 rad absorbs the
  // double rounding of their shared ends).
  constexpr double kTouch = 1e-12;
  VisibleExtent2d e;
  std::sort(pieces.begin(), pieces.end(), [](const Interval& x, const Interval& y) { return x.start < y.start; });
  std::vector<Interval> runs;
  for (const Interval& p : pieces) {
    e.angular_extent += p.width;
    if (!runs.empty() && p.start <= runs.back().start + runs.back().width + kTouch)
      runs.back().width = std::max(runs.back().width, p.start + p.width - runs.back().start);
    else
      runs.push_back(p);
  }
  if (circular && runs.size() > 1 && runs.back().start + runs.back().width + kTouch >= kTwoPi + runs.front().start) {
    runs.back().width = runs.front().start + kTwoPi + runs.front().width - runs.back().start;
    runs.erase(runs.begin());
  }
  for (const Interval& r : runs) e.largest_interval = std::max(e.largest_interval, r.width);
  return e;
}

}  // namespace

struct ExactVisibility2d::Impl {
  const Scene& scene;
  Box2 frame;  // the bounding box added to the arrangement; the eye must lie strictly inside
  std::vector<ExactFootprint> footprints;
  Arrangement arrangement;
  std::optional<Visibility> visibility;
  // Queries are serialised: Triangular_expansion_visibility_2 keeps scratch state per query,
  // and the lazy exact numbers shared by the footprints and the arrangement are refined in place
  // when a predicate needs more precision.
  mutable std::mutex mutex;

  Impl(const Scene& s, Box2 must_contain) : scene(s) {
    Box2 box = s.bounds().plan();
    if (!must_contain.empty()) box.extend(must_contain);
    if (box.empty()) box.extend(Vec2{0, 0});
    // A margin as wide as the scene (and at least 1 km) keeps the frame well away from the eye
    // and the buildings; its edges only close the visibility polygon, they belong to nothing.
    const double margin = std::max({1000.0, box.hi.x - box.lo.x, box.hi.y - box.lo.y});
    frame = {{std::floor(box.lo.x - margin), std::floor(box.lo.y - margin)},
             {std::ceil(box.hi.x + margin), std::ceil(box.hi.y + margin)}};
    footprints = exact_footprints(s);
    std::vector<Traits::X_monotone_curve_2> segments;
    for (const ExactFootprint& f : footprints)
      for (std::size_t k = 0; k < f.ring.size(); ++k) segments.emplace_back(f.ring[k], f.ring[(k + 1) % f.ring.size()]);
    const Point c[4] = {{frame.lo.x, frame.lo.y}, {frame.hi.x, frame.lo.y}, {frame.hi.x, frame.hi.y}, {frame.lo.x, frame.hi.y}};
    for (int k = 0; k < 4; ++k) segments.emplace_back(c[k], c[(k + 1) % 4]);
    // Footprints may touch or overlap one another; the sweep splits every curve at every crossing.
    CGAL::insert(arrangement, segments.begin(), segments.end());
    visibility.emplace(arrangement);
  }

  bool strictly_inside_frame(Vec2 p) const {
    return p.x > frame.lo.x && p.x < frame.hi.x && p.y > frame.lo.y && p.y < frame.hi.y;
  }

  bool on_frame(const Point& a, const Point& b) const {
    for (double x : {frame.lo.x, frame.hi.x})
      if (a.x() == x && b.x() == x) return true;
    for (double y : {frame.lo.y, frame.hi.y})
      if (a.y() == y && b.y() == y) return true;
    return false;
  }

  // Buildings whose footprint boundary holds the whole of [a, b] (two when walls coincide).
  void owners_of(const Point& a, const Point& b, std::vector<ObjectId>& out) const {
    out.clear();
    const Vec2 da = to_vec2(a), db = to_vec2(b);
    const Vec2 mid = (da + db) * 0.5;
    for (const ExactFootprint& f : footprints) {
      // A double-precision filter first: only edges passing within a loose tolerance of the
      // midpoint are tested exactly.
      const double tol = 1e-6 * (1.0 + std::abs(mid.x) + std::abs(mid.y));
      if (mid.x < f.box.lo.x - tol || mid.x > f.box.hi.x + tol || mid.y < f.box.lo.y - tol || mid.y > f.box.hi.y + tol)
        continue;
      for (std::size_t k = 0; k < f.ring.size(); ++k) {
        const Point& p = f.ring[k];
        const Point& r = f.ring[(k + 1) % f.ring.size()];
        const Vec2 dp = to_vec2(p), dr = to_vec2(r);
        const Vec2 e = dr - dp;
        if (std::abs(cross(e, mid - dp)) > tol * (1.0 + length(e))) continue;
        if (on_segment(p, r, a) && on_segment(p, r, b)) {
          out.push_back(f.id);
          break;
        }
      }
    }
  }

  Exact2dResult query(const Camera& camera) const {
    const Point eye(camera.position.x, camera.position.y);
    CGAL::Arr_naive_point_location<Arrangement> locator(arrangement);
    const auto location = locator.locate(eye);
    const auto* face = boost::get<Arrangement::Face_const_handle>(&location);
    if (!face) throw std::logic_error("exact_2d: the eye lies on an arrangement edge outside every footprint");
    Arrangement polygon;
    const Arrangement::Face_handle region = visibility->compute_visibility(eye, *face, polygon);
    const Wedge wedge = wedge_of(camera);
    const Vec2 eye2 = plan(camera.position);
    std::map<ObjectId, std::vector<Interval>> pieces;
    std::vector<ObjectId> owners;
    Exact2dResult result;
    auto edge = region->outer_ccb();
    do {
      ++result.visibility_polygon_edges;
      // Counter-clockwise around the star-shaped region, so every edge with positive angular
      // extent has the eye on its left; windows (radial edges) and walls seen edge-on are
      // collinear with the eye and subtend nothing.
      Point a = edge->source()->point(), b = edge->target()->point();
      if (CGAL::orientation(eye, a, b) != CGAL::LEFT_TURN) continue;
      if (on_frame(a, b)) continue;
      owners_of(a, b, owners);
      if (owners.empty())
        throw std::logic_error("exact_2d: a visibility-polygon edge lies on no footprint and not on the frame");
      if (!wedge.everything && !(clip(a, b, eye, wedge.normals[0]) && clip(a, b, eye, wedge.normals[1]))) continue;
      if (CGAL::orientation(eye, a, b) != CGAL::LEFT_TURN) continue;  // clipped down to a point
      const Vec2 va = to_vec2(a) - eye2, vb = to_vec2(b) - eye2;
      const double width = std::atan2(cross(va, vb), dot(va, vb));
      // Angles from the wedge's clockwise edge (perspective) or from +x (omnidirectional).
      const Vec2 ref = wedge.everything ? Vec2{1.0, 0.0} : wedge.right_edge;
      double start = std::atan2(cross(ref, va), dot(ref, va));
      if (wedge.everything && start < 0) start += kTwoPi;
      for (ObjectId id : owners) pieces[id].push_back({start, width});
    } while (++edge != region->outer_ccb());
    for (auto& [id, list] : pieces) {
      result.visible.push_back(id);
      result.extents[id] = merge(std::move(list), wedge.everything);
    }
    return result;
  }
};

namespace {

// The exact test behind "the eye is inside or on a building": closed footprint membership.
const ExactFootprint* footprint_holding(const std::vector<ExactFootprint>& footprints, Vec2 eye) {
  const Point q(eye.x, eye.y);
  for (const ExactFootprint& f : footprints) {
    if (!f.box.contains(eye)) continue;
    if (CGAL::bounded_side_2(f.ring.begin(), f.ring.end(), q, Kernel()) != CGAL::ON_UNBOUNDED_SIDE) return &f;
  }
  return nullptr;
}


bool level(const Camera& c) { return c.omnidirectional() || (c.pitch == 0.0 && c.roll == 0.0); }

// Whether a box may meet the view cone (the side planes only; near and far ignored).
bool may_meet_cone(const ViewTransform& v, const Box3& box) { return v.omnidirectional() || v.may_meet(box, /*depth=*/false); }

std::string name(const Building& b) { return "building " + std::to_string(b.id); }

}  // namespace

Exact2dApplicability check_exact_2d(const Scene& scene, const Camera& camera) {
  try {
    validate(camera);
  } catch (const InputError& e) {
    return {false, e.what()};
  }
  if (!scene.prisms_only()) return {false, "the scene holds mesh objects (not 2.5D)"};
  if (camera.orthographic()) return {false, "camera is orthographic"};
  if (!level(camera)) return {false, "camera is not level (pitch and roll must be 0)"};
  const double z = camera.position.z;
  for (const Building& b : scene.buildings)
    if (!(b.height > z)) return {false, name(b) + " is not taller than the eye"};
  const std::vector<ExactFootprint> footprints = exact_footprints(scene);
  if (const ExactFootprint* f = footprint_holding(footprints, plan(camera.position)))
    return {false, "the eye lies inside or on building " + std::to_string(f->id)};
  const ViewTransform volume(camera);
  const Vec3 forward = volume.forward();
  const Vec2 eye = plan(camera.position);
  double tallest = 0.0;
  for (const Building& b : scene.buildings)
    if (may_meet_cone(volume, b.bounds)) tallest = std::max(tallest, b.height);
  // Elevation of the highest ray in the view volume (the top plane of a level camera).
  const double rise = camera.omnidirectional() ? std::numeric_limits<double>::infinity() : std::tan(camera.vfov / 2);
  for (const Building& b : scene.buildings) {
    if (!may_meet_cone(volume, b.bounds)) continue;  // neither seen nor in the way of anything seen
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner{k & 1 ? b.bounds.hi.x : b.bounds.lo.x, k & 2 ? b.bounds.hi.y : b.bounds.lo.y,
                        k & 4 ? b.bounds.hi.z : b.bounds.lo.z};
      const double reach = camera.omnidirectional() ? length(corner - camera.position) : dot(forward, corner - camera.position);
      if (reach > camera.far) return {false, name(b) + " reaches beyond the far plane"};
    }
    if (!camera.omnidirectional() && min_distance(eye, b.bounds.plan()) * std::cos(camera.hfov / 2) < camera.near)
      return {false, name(b) + " may lie nearer than the near plane"};
    if (b.height < tallest && !(b.height >= z + max_distance(eye, b.bounds.plan()) * rise))
      return {false, name(b) + " is lower than the tallest building in view and low enough to be seen over"};
  }
  return {true, "level camera, every building taller than the eye, nothing can be seen over a building"};
}

bool exact_2d_applies(const Scene& scene, const Camera& camera) { return check_exact_2d(scene, camera).applies; }

ExactVisibility2d::ExactVisibility2d(const Scene& scene) : impl_(std::make_unique<Impl>(scene, Box2{})) {}
ExactVisibility2d::~ExactVisibility2d() = default;

Exact2dResult ExactVisibility2d::visible(const Camera& camera) const {
  const auto start = std::chrono::steady_clock::now();
  validate(camera);
  if (!level(camera))
    throw InputError("camera", camera.pitch != 0.0 ? "pitch" : "roll", "must be 0: the exact 2D oracle needs a level camera");
  for (const Building& b : impl_->scene.buildings)
    if (!(b.height > camera.position.z))
      throw InputError(name(b), "height", "is not taller than the eye (z = " + std::to_string(camera.position.z) +
                                              "): the exact 2D oracle needs every building taller than the eye");
  const Vec2 eye = plan(camera.position);
  std::lock_guard<std::mutex> lock(impl_->mutex);
  if (const ExactFootprint* f = footprint_holding(impl_->footprints, eye))
    throw InputError("camera", "position", "lies inside or on building " + std::to_string(f->id) +
                                               ": the exact 2D oracle needs the eye in free space");
  Exact2dResult result;
  if (impl_->strictly_inside_frame(eye)) {
    result = impl_->query(camera);
  } else {
    Box2 with_eye;
    with_eye.extend(eye);
    result = Impl(impl_->scene, with_eye).query(camera);  // an eye far outside the scene: a wider frame
  }
  result.elapsed_seconds = seconds_since(start);
  return result;
}

Exact2dResult exact_visible_2d(const Scene& scene, const Camera& camera) { return ExactVisibility2d(scene).visible(camera); }

}  // namespace cullcheck::oracle
