// More hard cases for the oracle-based horizon properties (ci/mutants/ shows what they kill),
// next to grazing_cameras.hpp's: each is a plain camera in a seeded city, so a counterexample
// replays as `cullcheck verify ... --camera '...'`, and each comes with the plan-geometry test
// (written here, shared with neither the engine nor the oracle) that says whether a case reached
// the situation it was written for, so that a property can count and assert how often it did.
//
//  - before_a_deep_facade: a low CVP B standing wholly in front of a taller CVP A's long facade,
//    seen by an eye that looks along the facade from nearer A than B. Every sight line through B
//    goes on into A, so B lies in A's azimuth span and below A's shadow, yet B is in front of A
//    and visible: a shadow may enter the horizon only once the sweep has passed its CVP's
//    farthest point, not its nearest.
//  - clipped_corner_draw: grazing_camera's eye just beyond a silhouette vertex a, with a far
//    enough off the view axis that it lies before the near plane although its plan distance
//    exceeds the near distance; the CVP's clipped corner hides nothing, and b shows through it.
//  - far_roof_draw: grazing_camera's far roof just under the near roof's shadow line, the eye
//    close to the near CVP so that the far one is several times farther: one rise by less than
//    the guard's height lifts the far roof over the near one.
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "generators/open_space.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "properties/grazing_cameras.hpp"

namespace cullcheck::properties {

namespace cases_detail {

inline double signed_area(const std::vector<Vec2>& ring) {
  double a = 0.0;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) a += cross(ring[j], ring[i]);
  return a / 2;
}

inline std::vector<detail::PrismRef> all_prisms(const Scene& scene) {
  std::vector<detail::PrismRef> prisms;
  for (std::size_t b = 0; b < scene.buildings.size(); ++b)
    for (std::size_t p = 0; p < scene.buildings[b].prisms.size(); ++p) prisms.push_back({b, p});
  return prisms;
}

inline double ring_distance(const std::vector<Vec2>& ring, Vec2 e) {
  double best = HUGE_VAL;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) best = std::min(best, distance_to_segment(e, ring[j], ring[i]));
  return best;
}

}  // namespace cases_detail

// --- A low building in front of a deep facade ---------------------------------------------------

// Whether B stands wholly in front of A seen from `eye`: every sight line through a vertex of B
// (moved 1% towards B's centre, so not a grazing line), continued 8 times as far, crosses A's ring.
inline bool wholly_in_front(const std::vector<Vec2>& A, const std::vector<Vec2>& B, Vec2 eye) {
  auto crosses = [](Vec2 p, Vec2 q, const std::vector<Vec2>& ring) {
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const Vec2 c = ring[j], d = ring[i];
      const double o1 = cross(q - p, c - p), o2 = cross(q - p, d - p), o3 = cross(d - c, p - c), o4 = cross(d - c, q - c);
      if (((o1 > 0) != (o2 > 0)) && ((o3 > 0) != (o4 > 0))) return true;
    }
    return false;
  };
  Vec2 centre{0, 0};
  for (Vec2 v : B) centre = centre + v;
  centre = centre * (1.0 / static_cast<double>(B.size()));
  for (Vec2 v : B) {
    const Vec2 w = v + (centre - v) * 0.01;
    if (!crosses(w, eye + (w - eye) * 8.0, A)) return false;
  }
  return true;
}

struct FacadeDraw {
  int occluder = 0, pick = 0;
  int eye_height = 0;  // 0: 1.7 m, 1: just over B's roof, 2: midway between the roofs
  generators::rcgen::FieldOfView fov;
};

// The case drawn: A (occluder) and B (target), and whether every sight line through a vertex of
// B, continued, meets A's facade while A's nearest point is nearer than B's (the situation).
struct FacadeCase {
  Grazing grazing;
  bool reached = false;
};

// The eye: for every occluder A (from the drawn one on) and every CVP B of another building at
// least 0.5 m lower, eyes 2-24 m from B's centre in 36 directions; the ones from which B stands
// wholly in front of A (wholly_in_front), A is nearer than B in plan and the eye stands in the
// open; the draw picks one of them all (`pick`), looking at B's centre.
inline FacadeCase before_a_deep_facade(const Scene& scene, const generators::OpenSpace& open, const FacadeDraw& draw) {
  FacadeCase out;
  const auto prisms = cases_detail::all_prisms(scene);
  if (prisms.size() < 2) return out;
  struct Found {
    std::size_t occluder, target;
    Vec2 eye;
  };
  std::vector<Found> found;
  auto centre_of = [](const std::vector<Vec2>& ring) {
    Vec2 c{0, 0};
    for (Vec2 v : ring) c = c + v;
    return c * (1.0 / static_cast<double>(ring.size()));
  };
  for (std::size_t i = 0; i < prisms.size(); ++i) {
    const std::size_t occluder = (static_cast<std::size_t>(draw.occluder) + i) % prisms.size();
    const ConvexVerticalPrism& A = scene.buildings[prisms[occluder].building].prisms[prisms[occluder].prism];
    for (std::size_t t = 0; t < prisms.size(); ++t) {
      if (prisms[t].building == prisms[occluder].building) continue;
      const ConvexVerticalPrism& B = scene.buildings[prisms[t].building].prisms[prisms[t].prism];
      if (!(B.height < A.height - 0.5)) continue;
      const Vec2 c = centre_of(B.ring);
      for (const double reach : {2.0, 5.0, 10.0, 24.0})
        for (int k = 0; k < 36; ++k) {
          const double psi = k * kTwoPi / 36;
          const Vec2 eye = c + Vec2{std::cos(psi), std::sin(psi)} * reach;
          if (cases_detail::ring_distance(A.ring, eye) >= cases_detail::ring_distance(B.ring, eye) ||
              !wholly_in_front(A.ring, B.ring, eye) || open.inside_building({eye.x, eye.y, 1.0}))
            continue;
          found.push_back({occluder, t, eye});
        }
    }
  }
  if (found.empty()) return out;
  const Found& f = found[static_cast<std::size_t>(draw.pick) % found.size()];
  const detail::PrismRef pa = prisms[f.occluder], pb = prisms[f.target];
  const ConvexVerticalPrism& A = scene.buildings[pa.building].prisms[pa.prism];
  const ConvexVerticalPrism& B = scene.buildings[pb.building].prisms[pb.prism];
  const Vec2 c = centre_of(B.ring);
  const double heights[] = {1.7, B.height + 0.3, (A.height + B.height) / 2};
  Camera cam;
  cam.position = {f.eye.x, f.eye.y, heights[draw.eye_height % 3]};
  cam.hfov = draw.fov.hfov;
  cam.vfov = draw.fov.vfov;
  cam.yaw = azimuth_of(c - f.eye);
  out.grazing.camera = cam;
  out.grazing.occluder = scene.buildings[pa.building].id;
  out.grazing.target = scene.buildings[pb.building].id;
  out.grazing.a = f.eye, out.grazing.b = c;
  out.grazing.usable = !open.inside_building(cam.position);
  out.reached = out.grazing.usable;
  return out;
}

inline rc::Gen<FacadeDraw> facade_draw() {
  using generators::rcgen::detail::int_in;
  return rc::gen::map(rc::gen::tuple(int_in(0, 10000), int_in(0, 100000), int_in(0, 2), generators::rcgen::field_of_view()),
                      [](const auto& t) {
                        FacadeDraw d;
                        std::tie(d.occluder, d.pick, d.eye_height, d.fov) = t;
                        return d;
                      });
}

// --- A corner before the near plane, off the view axis ------------------------------------------

// grazing_camera's draw with a at |look| hfov/2 off the axis and at plan distance
// near * lambda / cos(that angle), lambda between cos(angle) and 1: a lies before the near plane
// (depth near * lambda) but beyond the near distance, so only the guard at the view's corners
// keeps its CVP from casting a shadow. b hides 1-20 bins behind a, where the sight line crosses
// the CVP close to a, within the clipped corner.
inline rc::Gen<GrazingDraw> clipped_corner_draw() {
  using generators::rcgen::detail::int_in;
  return rc::gen::map(
      rc::gen::tuple(grazing_draw(), rc::gen::element(0.3, 1.0, 0.5), int_in(80, 120), int_in(40, 70), int_in(60, 95),
                     rc::gen::arbitrary<bool>(), rc::gen::element(0.5, 0.3, 0.7, 0.9), int_in(1, 20)),
      [](const auto& t) {
        auto [d, near, hfov_deg, vfov_deg, look, left, lambda_share, behind] = t;
        d.near = near;
        d.fov = {generators::radians(hfov_deg * 1.0), generators::radians(vfov_deg * 1.0)};
        d.look = (left ? 1 : -1) * look / 100.0;
        const double off_axis = std::abs(d.look) * d.fov.hfov / 2;
        const double lambda = std::cos(off_axis) + lambda_share * (1.0 - std::cos(off_axis));
        d.distance = near * lambda / std::cos(off_axis);
        d.offset_bins = -behind;
        d.offset_metres.reset();
        d.height = 0;
        return d;
      });
}

// Whether the occluder's silhouette vertex a lies in the horizontal view, before the near plane,
// while the occluder's CVP is farther than the near distance in plan (the clipped-corner case).
// For a level camera: depth is the plan distance along the view axis.
inline bool corner_before_near_plane(const Scene& scene, const Grazing& g) {
  if (!g.usable || g.camera.pitch != 0.0 || g.camera.roll != 0.0 || g.camera.omnidirectional()) return false;
  const Vec2 e = plan(g.camera.position), axis{std::cos(g.camera.yaw), std::sin(g.camera.yaw)};
  const Vec2 to_a = g.a - e;
  const double depth = dot(to_a, axis), off_axis = std::abs(std::atan2(cross(axis, to_a), depth));
  if (!(depth < g.camera.near) || !(off_axis < g.camera.hfov / 2)) return false;
  for (const Building& b : scene.buildings) {
    if (b.id != g.occluder) continue;
    for (const ConvexVerticalPrism& prism : b.prisms)
      if (cases_detail::ring_distance(prism.ring, e) <= g.camera.near) return false;
  }
  return true;
}

// --- A far roof that a rise lifts over a near one -----------------------------------------------

// grazing_camera's elevation draw with the eye below the level (heights 6 and 7: B's roof at b on
// the line over A's roof at A's farther tangent vertex, the eye 5 or 30 cm lower) 1-5 m beyond a, so that B is many times farther
// than A and a rise of the eye by a few decimetres lowers A's shadow line below B's roof.
inline rc::Gen<GrazingDraw> far_roof_draw() {
  using generators::rcgen::detail::int_in;
  return rc::gen::map(rc::gen::tuple(grazing_draw(), int_in(6, 7), rc::gen::element(2.0, 1.0, 3.0, 5.0), int_in(0, 40)),
                      [](const auto& t) {
                        auto [d, height, distance, half_bins] = t;
                        d.height = height;
                        d.distance = distance;
                        d.offset_bins = -half_bins * 0.5;
                        d.offset_metres.reset();
                        d.near = 0.1;
                        return d;
                      });
}

// far_roof_draw's camera, with the far CVP chosen for depth: from the drawn target on, the first
// of 24 whose b is at least 6 times as far from the eye as a, with the eye set by the roof line
// (not left at the 1.7 m fallback); the drawn target's camera when none is.
inline Grazing far_roof_camera(const Scene& scene, const generators::OpenSpace& open, GrazingDraw draw) {
  const int first = draw.target;
  for (int k = 0; k < 24; ++k) {
    draw.target = first + k;
    const Grazing g = grazing_camera(scene, open, draw);
    const Vec2 e = plan(g.camera.position);
    if (g.usable && g.camera.position.z != 1.7 && length(g.b - e) >= 6 * length(g.a - e)) return g;
  }
  draw.target = first;
  return grazing_camera(scene, open, draw);
}

}  // namespace cullcheck::properties
