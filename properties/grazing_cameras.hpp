// Hard cases for the oracle-based properties (ci/mutants/ shows what they kill): cameras in a
// generated city placed so that a far CVP's silhouette vertex b lies just beside, or just behind,
// a near CVP's silhouette vertex a. The eye stands on the two CVPs' outer common tangent line,
// `distance` beyond a, moved off the line so that b shows `offset` radians beside a (negative:
// hidden behind a), then turned about a so that a's azimuth falls at `bin_phase` of a horizon bin
// (4096 bins over 2π, the engine's default: exactly on a bin edge, just after one, mid-bin, just
// before the next). So the far CVP is hidden except for a sliver narrower than one bin, a shadow
// edge and a tested span's edge share a bin, and a small move of the eye (a ΔH step, an ε-disc)
// uncovers or hides b. Eyes near a reach the near plane; eyes by the roof lines see occluders
// just below and just above the eye.
//
// The scene is one of the property generators' seeded cities, and the camera is a plain camera,
// so a counterexample prints as the usual `cullcheck verify ... --camera '...'` replay. A case
// whose eye lands inside a building, or whose city has no such pair, is flagged unusable (the
// properties pass it, tagged, rather than discard it: RapidCheck gives up after many discards).
#pragma once

#include <rapidcheck.h>

#include <cmath>
#include <optional>
#include <tuple>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "generators/angles.hpp"
#include "generators/open_space.hpp"
#include "generators/rapidcheck_gens.hpp"

namespace cullcheck::properties {

// What the generator draws (all shrink towards the first, simplest choice).
struct GrazingDraw {
  int occluder = 0, target = 0;  // CVP picks (modulo the scene's CVP count)
  int tangent = 0;               // which of the two outer common tangents
  double distance = 5.0;         // eye beyond a along the tangent, metres
  double offset_bins = 0.5;      // b beside a, in horizon bins (negative: behind a)
  // When set, the eye's distance off the tangent line instead, in metres (negative: b hidden):
  // an eye -f ε off it sees b once it moves more than f ε to the free side.
  std::optional<double> offset_metres;
  double bin_phase = 0.5;        // where a's azimuth falls in its bin, 0..1
  int height = 0;                // eye height: street, at A's roof +-, above every roof, B's roof
                                 // just under or over A's shadow (4-7)
  double look = 0.0;             // yaw off a's direction, as a fraction of hfov / 2
  generators::rcgen::FieldOfView fov;
  double near = 0.1;
};

inline constexpr double kGrazingBinWidth = kTwoPi / 4096;

struct Grazing {
  Camera camera;
  bool usable = false;
  ObjectId occluder = 0, target = 0;  // building ids of the two CVPs
  Vec2 a, b;                          // the silhouette vertices
  Vec2 free_side;                     // unit normal of the tangent line, away from both CVPs
};

namespace detail {

struct PrismRef {
  std::size_t building, prism;
};

// The vertex of `ring` strictly extreme on the line through p with direction d (every other
// vertex strictly on one side), and that side (+1 left, -1 right); none when an edge lies on it.
inline std::optional<int> supporting_side(const std::vector<Vec2>& ring, Vec2 p, Vec2 d, std::size_t skip) {
  int side = 0;
  const double scale = length(d);
  for (std::size_t k = 0; k < ring.size(); ++k) {
    if (k == skip) continue;
    const double c = cross(d, ring[k] - p) / scale;
    const int s = c > 1e-6 ? 1 : (c < -1e-6 ? -1 : 0);
    if (s == 0 || (side != 0 && s != side)) return std::nullopt;
    side = s;
  }
  return side;
}

}  // namespace detail

// The camera of `draw` in `scene` (see the header comment).
inline Grazing grazing_camera(const Scene& scene, const generators::OpenSpace& open, const GrazingDraw& draw) {
  Grazing out;
  std::vector<detail::PrismRef> prisms;
  for (std::size_t b = 0; b < scene.buildings.size(); ++b)
    for (std::size_t p = 0; p < scene.buildings[b].prisms.size(); ++p) prisms.push_back({b, p});
  if (prisms.size() < 2) return out;
  const detail::PrismRef pa = prisms[static_cast<std::size_t>(draw.occluder) % prisms.size()];
  detail::PrismRef pb = prisms[static_cast<std::size_t>(draw.target) % prisms.size()];
  if (pb.building == pa.building) pb = prisms[(static_cast<std::size_t>(draw.target) + 1) % prisms.size()];
  if (pb.building == pa.building) return out;
  const ConvexVerticalPrism& A = scene.buildings[pa.building].prisms[pa.prism];
  const ConvexVerticalPrism& B = scene.buildings[pb.building].prisms[pb.prism];
  // The outer common tangents: vertex pairs whose line supports both rings on the same side.
  struct Tangent {
    Vec2 a, b;
    int side;
  };
  std::vector<Tangent> tangents;
  for (std::size_t i = 0; i < A.ring.size(); ++i)
    for (std::size_t j = 0; j < B.ring.size(); ++j) {
      const Vec2 a = A.ring[i], b = B.ring[j], d = a - b;
      if (length(d) < 1e-3) continue;
      const auto sa = detail::supporting_side(A.ring, a, d, i), sb = detail::supporting_side(B.ring, a, d, j);
      if (sa && sb && *sa == *sb) tangents.push_back({a, b, *sa});
    }
  if (tangents.empty()) return out;
  // The eye for tangent t (see the header comment) and the free side's normal.
  auto eye_for = [&](const Tangent& t) {
    const Vec2 u = (t.a - t.b) * (1.0 / length(t.a - t.b));
    // Both rings lie on side t.side of the line (cross(d, x - a) sign); the free side is the other.
    const Vec2 left{-u.y, u.x};  // cross(u, left) > 0
    const Vec2 free_side = left * static_cast<double>(-t.side);
    // From an eye at a + distance·u + s·free_side, b shows beside a by about
    // s (1/distance - 1/(distance + |ab|)) radians.
    const double ab = length(t.a - t.b), r = draw.distance;
    const double per_metre = 1.0 / r - 1.0 / (r + ab);
    const double s = draw.offset_metres ? *draw.offset_metres : draw.offset_bins * kGrazingBinWidth / per_metre;
    Vec2 eye = t.a + u * r + free_side * s;
    // Turn the eye about a so that a's azimuth falls at bin_phase of its bin.
    const Vec2 to_a = t.a - eye;
    const double azimuth = azimuth_of(to_a);
    const double wanted = (std::floor(azimuth / kGrazingBinWidth) + draw.bin_phase) * kGrazingBinWidth;
    eye = t.a - Vec2{std::cos(wanted), std::sin(wanted)} * length(to_a);
    return std::pair{eye, free_side};
  };
  std::size_t pick = static_cast<std::size_t>(draw.tangent) % tangents.size();
  // For the elevation cases (height 4-7) prefer a tangent whose a is A's farther tangent vertex
  auto a_is_far_tangent = [&](const Tangent& t, Vec2 eye) {
    const Vec2 to = t.a - eye;
    for (Vec2 v : A.ring) {
      const double angle = std::atan2(cross(to, v - eye), dot(to, v - eye));
      if ((angle > 1e-12 || angle < -1e-12) && length(v - eye) > length(to)) {
        // v is off a's direction; it is a tangent vertex only if it is extreme on its side.
        bool extreme = true;
        for (Vec2 w : A.ring) {
          const double other = std::atan2(cross(to, w - eye), dot(to, w - eye));
          extreme = extreme && (angle > 0 ? other <= angle : other >= angle);
        }
        if (extreme) return false;
      }
    }
    return true;
  };
  // ... and b is B's nearest vertex, so that B's highest slope is its roof at b.
  auto b_is_nearest = [&](const Tangent& t, Vec2 eye) {
    for (Vec2 v : B.ring)
      if (length(v - eye) < length(t.b - eye)) return false;
    return true;
  };
  if (draw.height >= 4)
    for (std::size_t k = 0; k < tangents.size(); ++k) {
      const std::size_t q = (pick + k) % tangents.size();
      const Vec2 e = eye_for(tangents[q]).first;
      if (a_is_far_tangent(tangents[q], e) && b_is_nearest(tangents[q], e)) {
        pick = q;
        break;
      }
    }
  const Tangent& t = tangents[pick];
  const auto [eye, free_side] = eye_for(t);

  double z = 1.7;
  switch (draw.height) {
    case 1: z = A.height - 0.3; break;
    case 2: z = A.height + 0.3; break;
    case 3: z = open.bounds().hi.z + 5.0; break;
    case 4: case 5: case 6: case 7: {
      // B's roof at b just below (4, 5) or above (6, 7) the line over A's roof at its farther
      // tangent vertex (the conservative shadow's elevation for a roof above the eye): solve
      // (h_A - z) / D_A = (h_B - z) / |b - eye| for z, then move the eye by a few centimetres.
      const Vec2 to = t.a - eye;
      double lo = 0.0, hi = 0.0, d_lo = length(to), d_hi = d_lo, d_b = 0.0;
      for (Vec2 v : A.ring) {
        const double angle = std::atan2(cross(to, v - eye), dot(to, v - eye));
        if (angle < lo) lo = angle, d_lo = length(v - eye);
        if (angle > hi) hi = angle, d_hi = length(v - eye);
      }
      d_b = length(t.b - eye);  // B's roof at b, the vertex just beside (or behind) a
      const double d_a = std::max(d_lo, d_hi);
      if (d_b > d_a * 1.05) {
        const double level = (A.height * d_b - B.height * d_a) / (d_b - d_a);
        const double nudge[4] = {0.05, 0.3, -0.05, -0.3};
        z = level + nudge[draw.height - 4];
      }
      if (!(z < A.height - 0.05)) z = 1.7;
      break;
    }
    default: break;
  }
  if (!(z > 0.05)) z = 1.7;
  Camera c;
  c.position = {eye.x, eye.y, z};
  c.hfov = draw.fov.hfov;
  c.vfov = draw.fov.vfov;
  c.yaw = std::fmod(azimuth_of(t.a - eye) + (c.omnidirectional() ? 0.0 : draw.look * c.hfov / 2) + 2 * kTwoPi, kTwoPi);
  // Above every roof, look down at a so that both CVPs are in view.
  if (draw.height == 3) c.pitch = -std::atan2(z - A.height, length(t.a - eye));
  c.near = draw.near;
  c.far = std::max(c.far, 4 * c.near);
  out.camera = c;
  out.occluder = scene.buildings[pa.building].id;
  out.target = scene.buildings[pb.building].id;
  out.a = t.a, out.b = t.b, out.free_side = free_side;
  out.usable = !open.inside_building(c.position) && length(t.a - eye) > 1e-3;
  return out;
}

// An eye 1, 3 or 9 times `reach` metres from a vertex of a deep CVP A, placed (among 36
// directions around each vertex, the `pick`-th that qualifies) so that another building's CVP B stands between the eye
// and A's far part while A's nearest point is nearer than B's: when B is tested, A's shadow must
// not be in the horizon yet (it is merged once the sweep passes A's farthest point). The camera
// looks at B. Unusable when no direction qualifies.
struct FrontDraw {
  int occluder = 0, target = 0, vertex = 0, pick = 0;
  double reach = 3.0;
  double z = 1.7;
  generators::rcgen::FieldOfView fov;
};

inline Grazing in_front_of_deep_occluder(const Scene& scene, const generators::OpenSpace& open, const FrontDraw& draw) {
  Grazing out;
  std::vector<detail::PrismRef> prisms;
  for (std::size_t b = 0; b < scene.buildings.size(); ++b)
    for (std::size_t p = 0; p < scene.buildings[b].prisms.size(); ++p) prisms.push_back({b, p});
  if (prisms.size() < 2) return out;
  const detail::PrismRef pa = prisms[static_cast<std::size_t>(draw.occluder) % prisms.size()];
  const ConvexVerticalPrism& A = scene.buildings[pa.building].prisms[pa.prism];
  auto segment_hits_ring = [](Vec2 p, Vec2 q, const std::vector<Vec2>& ring) {
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const Vec2 c = ring[j], d = ring[i];
      const double o1 = cross(q - p, c - p), o2 = cross(q - p, d - p), o3 = cross(d - c, p - c), o4 = cross(d - c, q - c);
      if (((o1 > 0) != (o2 > 0)) && ((o3 > 0) != (o4 > 0))) return true;
    }
    return false;
  };
  auto min_distance_to = [](const std::vector<Vec2>& ring, Vec2 e) {
    double best = HUGE_VAL;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) best = std::min(best, distance_to_segment(e, ring[j], ring[i]));
    return best;
  };
  // Candidate (eye, target) pairs in a fixed order; the draw picks one.
  std::vector<std::pair<Vec2, std::size_t>> found;
  for (std::size_t v = 0; v < A.ring.size(); ++v)
  for (const double reach : {draw.reach, 3 * draw.reach, 9 * draw.reach})
  for (int k = 0; k < 36; ++k) {
    const double psi = k * kTwoPi / 36;
    const Vec2 e = A.ring[(v + static_cast<std::size_t>(draw.vertex)) % A.ring.size()] + Vec2{std::cos(psi), std::sin(psi)} * reach;
    if (open.inside_building({e.x, e.y, draw.z})) continue;
    const double near_a = min_distance_to(A.ring, e);
    for (std::size_t t = 0; t < prisms.size(); ++t) {
      if (prisms[t].building == pa.building) continue;
      const ConvexVerticalPrism& B = scene.buildings[prisms[t].building].prisms[prisms[t].prism];
      if (!(min_distance_to(B.ring, e) > near_a)) continue;
      // Some vertex of B (or a point a little inside it) in front of A: the sight line through it,
      // continued, meets A.
      Vec2 c{0, 0};
      for (Vec2 v : B.ring) c = c + v;
      c = c * (1.0 / static_cast<double>(B.ring.size()));
      bool in_front = false;
      for (Vec2 v : B.ring) {
        const Vec2 p = v + (c - v) * 0.01;
        in_front = in_front || segment_hits_ring(p, e + (p - e) * 8.0, A.ring);
      }
      if (in_front) found.push_back({e, t});
    }
  }
  if (found.empty()) return out;
  const auto& [e, t] = found[static_cast<std::size_t>(draw.pick + draw.target) % found.size()];
  const ConvexVerticalPrism& B = scene.buildings[prisms[t].building].prisms[prisms[t].prism];
  Vec2 c{0, 0};
  for (Vec2 v : B.ring) c = c + v;
  c = c * (1.0 / static_cast<double>(B.ring.size()));
  Camera cam;
  cam.position = {e.x, e.y, draw.z};
  cam.hfov = draw.fov.hfov;
  cam.vfov = draw.fov.vfov;
  cam.yaw = azimuth_of(c - e);
  out.camera = cam;
  out.occluder = scene.buildings[pa.building].id;
  out.target = scene.buildings[prisms[t].building].id;
  out.a = e, out.b = c;
  out.usable = true;
  return out;
}

inline rc::Gen<FrontDraw> front_draw() {
  using generators::rcgen::detail::int_in;
  return rc::gen::map(rc::gen::tuple(int_in(0, 10000), int_in(0, 10000), int_in(0, 7), int_in(0, 1000),
                                     rc::gen::element(3.0, 1.0, 8.0, 0.5, 20.0), rc::gen::element(1.7, 0.5, 6.0, 15.0),
                                     generators::rcgen::field_of_view()),
                      [](const auto& t) {
                        FrontDraw d;
                        std::tie(d.occluder, d.target, d.vertex, d.pick, d.reach, d.z, d.fov) = t;
                        return d;
                      });
}

// Draws for grazing_camera: mostly sub-bin offsets either side of a, any bin phase (the edges on
// purpose), eyes 0.05-60 m beyond a.
inline rc::Gen<GrazingDraw> grazing_draw() {
  using generators::rcgen::detail::int_in;
  const auto offset = rc::gen::weightedOneOf<double>(
      {{4, rc::gen::map(int_in(-40, 40), [](int k) { return k / 20.0; })},          // ±2 bins
       {1, rc::gen::map(int_in(-200, 200), [](int k) { return k * 1.0; })}});       // ±200 bins (0.3 rad)
  const auto phase = rc::gen::weightedOneOf<double>(
      {{1, rc::gen::element(0.0, 1e-9, 0.5, 1.0 - 1e-9)}, {3, rc::gen::map(int_in(0, 999), [](int k) { return k / 1000.0; })}});
  const auto distance = rc::gen::element(5.0, 1.0, 20.0, 0.3, 60.0, 0.05, 0.12);
  const auto look = rc::gen::map(int_in(-95, 95), [](int k) { return k / 100.0; });
  return rc::gen::map(rc::gen::tuple(int_in(0, 10000), int_in(0, 10000), int_in(0, 1), distance, offset, phase, int_in(0, 7),
                                     look, generators::rcgen::field_of_view(), rc::gen::element(0.1, 0.01, 0.3, 1.0)),
                      [](const auto& t) {
                        GrazingDraw d;
                        std::tie(d.occluder, d.target, d.tangent, d.distance, d.offset_bins, d.bin_phase, d.height, d.look,
                                 d.fov, d.near) = t;
                        return d;
                      });
}

}  // namespace cullcheck::properties
