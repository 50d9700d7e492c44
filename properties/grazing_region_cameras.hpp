// Hard cases for the from-region methods' vertical shrink (thesis Eq. 9-14, and what the
// corrected variant puts in their place, region_shrinking.hpp): an ε-disc whose centre C sees a
// target building B wholly behind a near CVP A, well inside A's span even after Eq. 4-6 narrow
// it, and beyond A's farthest point by more than 2ε, so only A's shadow's elevation decides.
// The eye height is solved so that B's roof, seen from C, lies strictly between the line over
// A's roof that C itself sees (the conservative shadow's slope, s = r / d) and the line the
// shrink lowers it to (r / (d + ε) above the eye's height, r / (d - ε) below it): a fraction
// `between` of the way from the first to the second. From C, B is hidden; from the disc's
// point farthest from B (A taller than the eye) or nearest to it (A lower), A's roof line drops
// (rises) by more than B's, and B's roof shows over A. A method that keeps C's elevation for the
// whole disc culls B there; the oracle sees it.
//
// Which slope C sees: A taller than the eye hides what lies below the line over the farther of
// its two tangent vertices (every sight line through A's span enters A on its near chain, which
// lies within that distance d); A lower than the eye hides what lies below the line over the
// nearest point d of its far chain (the sight line leaves A there at the earliest).
//
// The geometry is written here (plan vectors only), shared with neither the engine nor the
// oracle. A case whose scene has no such pair is flagged unusable (properties pass it, tagged).
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "generators/angles.hpp"
#include "generators/open_space.hpp"
#include "generators/rapidcheck_gens.hpp"

namespace cullcheck::properties {

// What the generator draws (each shrinks towards the first choice).
struct BehindOccluderDraw {
  int occluder = 0, target = 0;  // where the search for a pair starts (modulo the CVP counts)
  double radius = 1.0;           // ε, metres
  double clearance = 3.0;        // C beyond A's circumcircle, along the line from B's centre through A's
  double between = 0.5;          // B's roof at this fraction from C's shadow line to the shrunk one
  bool above = false;            // eye above A's roof (the lower-occluder shrink)
};

struct BehindOccluder {
  Camera centre;             // perspective, looking at B's centre, at the solved eye height
  bool usable = false;
  ObjectId occluder = 0, target = 0;
  Vec2 away;                 // unit plan vector from B's centre towards C (the disc's back)
  double radius = 1.0;
};

namespace behind_detail {

inline Vec2 centroid(const std::vector<Vec2>& ring) {
  Vec2 c{0, 0};
  for (Vec2 v : ring) c = c + v;
  return c * (1.0 / static_cast<double>(ring.size()));
}
inline double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double len2 = dot(d, d);
  const double t = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  return length(p - (a + d * t));
}
// Plan distance from p to a ring's boundary (p outside it).
inline double ring_distance(const std::vector<Vec2>& ring, Vec2 p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) best = std::min(best, segment_distance(p, ring[j], ring[i]));
  return best;
}
// Nearest point of the far chain (edges of the counter-clockwise ring that face away from p).
inline double far_chain_distance(const std::vector<Vec2>& ring, Vec2 p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    if (cross(ring[i] - ring[j], p - ring[j]) > 0.0) best = std::min(best, segment_distance(p, ring[j], ring[i]));
  return best;
}

}  // namespace behind_detail

// The case of `draw` in `scene` (see the header comment): the first pair (A, B) from the draw's
// starting picks that qualifies, B a single-CVP building of another building than A's.
inline BehindOccluder behind_occluder(const Scene& scene, const generators::OpenSpace& open, const BehindOccluderDraw& draw) {
  using namespace behind_detail;
  BehindOccluder out;
  out.radius = draw.radius;
  struct Ref {
    std::size_t building, prism;
  };
  std::vector<Ref> prisms;
  std::vector<std::size_t> targets;
  for (std::size_t b = 0; b < scene.buildings.size(); ++b) {
    for (std::size_t p = 0; p < scene.buildings[b].prisms.size(); ++p) prisms.push_back({b, p});
    if (scene.buildings[b].prisms.size() == 1) targets.push_back(b);
  }
  if (prisms.size() < 2 || targets.empty()) return out;
  const double eps = draw.radius, t = draw.between;
  const double margin = 0.01;  // radians (about 6.5 horizon bins) inside the narrowed span
  const std::size_t tries_a = std::min<std::size_t>(prisms.size(), 40), tries_b = std::min<std::size_t>(targets.size(), 60);
  for (std::size_t ka = 0; ka < tries_a; ++ka) {
    const Ref ra = prisms[(static_cast<std::size_t>(draw.occluder) + ka) % prisms.size()];
    const ConvexVerticalPrism& A = scene.buildings[ra.building].prisms[ra.prism];
    const Vec2 ca = centroid(A.ring);
    double circum = 0.0;
    for (Vec2 v : A.ring) circum = std::max(circum, length(v - ca));
    for (std::size_t kb = 0; kb < tries_b; ++kb) {
      const std::size_t b = targets[(static_cast<std::size_t>(draw.target) + kb) % targets.size()];
      if (b == ra.building) continue;
      const ConvexVerticalPrism& B = scene.buildings[b].prisms[0];
      const Vec2 cb = centroid(B.ring);
      if (length(ca - cb) < 1e-6) continue;
      const Vec2 away = (ca - cb) * (1.0 / length(ca - cb));
      const Vec2 c = ca + away * (circum + draw.clearance);
      // A's span from C and its tangent vertices, as angles from the direction C -> B.
      const Vec2 look = away * -1.0;
      auto angle = [&](Vec2 p) { return std::atan2(cross(look, p - c), dot(look, p - c)); };
      double lo = HUGE_VAL, hi = -HUGE_VAL, d_lo = 0.0, d_hi = 0.0, farthest_a = 0.0;
      for (Vec2 v : A.ring) {
        const double a = angle(v);
        if (a < lo) lo = a, d_lo = length(v - c);
        if (a > hi) hi = a, d_hi = length(v - c);
        farthest_a = std::max(farthest_a, length(v - c));
      }
      if (!(d_lo > eps && d_hi > eps)) continue;
      const double narrowed_lo = lo + std::asin(eps / d_lo) + margin, narrowed_hi = hi - std::asin(eps / d_hi) - margin;
      bool inside = narrowed_hi > narrowed_lo;
      double near_b = HUGE_VAL, far_b = 0.0;
      for (Vec2 v : B.ring) {
        const double a = angle(v);
        inside = inside && a > narrowed_lo && a < narrowed_hi;
        far_b = std::max(far_b, length(v - c));
      }
      near_b = ring_distance(B.ring, c);
      // Wholly behind A's farthest point, by more than the 2ε a disc viewpoint may reorder.
      if (!inside || !(near_b > farthest_a + 2 * eps + 0.1)) continue;
      if (!(ring_distance(A.ring, c) > eps + 0.2) || !open.is_open(c, eps * 1.05 + 0.05)) continue;
      // The eye height that puts B's roof at slope r / D from C, D between C's and the shrunk
      // shadow's distance, and far enough that the disc's edge sees it over A.
      double z = -1.0;
      if (!draw.above) {
        const double d = std::max(d_lo, d_hi), D = d + t * eps;
        if (!(near_b > 1.2 * D / (1.0 - t))) continue;
        z = (A.height * near_b - B.height * D) / (near_b - D);
        if (!(z > 0.3 && z < A.height - 0.3)) continue;
      } else {
        const double d = far_chain_distance(A.ring, c), D = d - t * eps;
        if (!(B.height < A.height) || !(D > 0.5) || !(far_b > 1.2 * D / (1.0 - t))) continue;
        z = (A.height * far_b - B.height * D) / (far_b - D);
        if (!(z > A.height + 0.3 && z < A.height + 60.0)) continue;
      }
      if (open.inside_building({c.x, c.y, z})) continue;
      Camera cam;
      cam.position = {c.x, c.y, z};
      cam.yaw = azimuth_of(cb - c);
      cam.hfov = generators::radians(90.0);
      cam.vfov = generators::radians(60.0);
      cam.near = 0.1;
      out.centre = cam;
      out.usable = true;
      out.occluder = scene.buildings[ra.building].id;
      out.target = scene.buildings[b].id;
      out.away = away;
      return out;
    }
  }
  return out;
}

inline rc::Gen<BehindOccluderDraw> behind_occluder_draw() {
  using generators::rcgen::detail::int_in;
  return rc::gen::map(rc::gen::tuple(int_in(0, 10000), int_in(0, 10000), rc::gen::element(1.0, 0.5, 2.0, 4.0),
                                     rc::gen::element(3.0, 1.0, 6.0, 12.0), rc::gen::element(0.5, 0.25, 0.75),
                                     rc::gen::arbitrary<bool>()),
                      [](const auto& tuple) {
                        BehindOccluderDraw d;
                        std::tie(d.occluder, d.target, d.radius, d.clearance, d.between, d.above) = tuple;
                        return d;
                      });
}

}  // namespace cullcheck::properties
