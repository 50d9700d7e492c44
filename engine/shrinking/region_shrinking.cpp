#include "engine/shrinking/region_shrinking.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/elapsed.hpp"
#include "engine/horizon/horizon_sweep.hpp"
#include "engine/shrinking/region_sweep.hpp"

namespace cullcheck {
namespace {

struct ShrunkShadow {
  AzimuthSpan span;
  double slope;
};

// Eq. 4-6, the horizontal shrink both adjustable variants share: the span narrowed at each end
// by asin(ε / distance of that end's tangent vertex); none when a tangent vertex lies within ε
// (Eq. 4-5 undefined) or nothing is left.
struct NarrowedSpan {
  AzimuthSpan span;
  double to_e, to_a;  // |CE| (E at α_min) and |AC| (A at α_max)
};
std::optional<NarrowedSpan> narrowed_span(const ConvexVerticalPrism& prism, Vec2 c, const ConvexSpan& span, double epsilon) {
  const double to_e = length(prism.ring[span.first_tangent] - c);
  const double to_a = length(prism.ring[span.last_tangent] - c);
  if (!(to_e > epsilon) || !(to_a > epsilon)) return std::nullopt;
  const AzimuthSpan shrunk{span.span.begin + std::asin(epsilon / to_e), span.span.end - std::asin(epsilon / to_a),
                           span.span.slack};
  if (!(shrunk.end > shrunk.begin)) return std::nullopt;
  return NarrowedSpan{shrunk, to_e, to_a};
}

// The published shrunk shadow of one CVP seen from the disc's centre C (thesis Eq. 1-16), or
// none when nothing is left of it. `span` is its span from C; the elevation β_min is the
// published rule's (the lower of the two tangent vertices) and d_X that vertex's distance.
std::optional<ShrunkShadow> published_shrunk_shadow(const ConvexVerticalPrism& prism, Vec3 eye, const ConvexSpan& span,
                                                    double epsilon) {
  const auto narrowed = narrowed_span(prism, plan(eye), span, epsilon);
  if (!narrowed) return std::nullopt;
  const auto [shrunk, to_e, to_a] = *narrowed;
  // β_min and the distance of the vertex that gives it.
  const double h_x = prism.height, h_c = eye.z;
  const double rise = h_x - h_c;
  const double d = rise / to_e <= rise / to_a ? to_e : to_a;
  const double beta_min = std::atan2(rise, d);
  double beta_f, beta_n;
  if (h_x < h_c) {  // Eq. 13-14, as printed (h_C + h_X)
    beta_f = std::atan2(d, h_c + h_x);
    beta_n = std::atan2(d - epsilon, h_c + h_x);
  } else {  // Eq. 9-10
    beta_f = std::atan2(epsilon + d, rise);
    beta_n = std::atan2(d, rise);
  }
  const double beta_s = beta_f - beta_n;          // Eq. 11
  const double beta_min_s = beta_min - beta_s;    // Eq. 12
  if (!(beta_min_s > -kPi / 2)) return std::nullopt;
  return ShrunkShadow{shrunk, std::tan(beta_min_s)};
}

// The corrected variant's shadow (region_shrinking.hpp): Eq. 4-6's horizontal shrink, the
// conservative rule's slope s = r / d shrunk to the sight line from the disc's farthest
// (r > 0) or nearest (r < 0) point.
std::optional<ShrunkShadow> corrected_shrunk_shadow(const ConvexVerticalPrism& prism, Vec3 eye, const ConvexSpan& span,
                                                    double epsilon) {
  // A CVP that reaches into the disc has viewpoints beside or behind it: no shadow (the ledger's
  // counterexample to the published method has a wall crossing the disc between its tangents).
  if (!(min_boundary_distance(prism.ring, plan(eye)) > epsilon)) return std::nullopt;
  const auto narrowed = narrowed_span(prism, plan(eye), span, epsilon);
  if (!narrowed) return std::nullopt;
  const AzimuthSpan shrunk = narrowed->span;
  const double slope = shadow_slope(ShadowRule::conservative, prism, eye, span);
  const double rise = prism.height - eye.z;
  if (rise == 0.0 || slope == 0.0) return ShrunkShadow{shrunk, 0.0};
  const double d = rise / slope;  // the distance of the shadow's edge
  if (!(d > 0.0)) return std::nullopt;
  if (rise > 0.0) return ShrunkShadow{shrunk, rise / (d + epsilon)};
  if (!(d > epsilon)) return std::nullopt;
  return ShrunkShadow{shrunk, rise / (d - epsilon)};
}

}  // namespace

PublishedShadowShrinking::PublishedShadowShrinking(const Scene& scene, const MethodOptions& options, bool corrected,
                                                   bool narrow_targets)
    : scene_(scene),
      options_(options),
      quadtree_(scene, options.quadtree_leaf_size),
      horizon_(options.horizon_bins),
      corrected_(corrected),
      narrow_targets_(corrected && narrow_targets) {}

CullResult PublishedShadowShrinking::cull_region(const ViewRegion& region) { return sweep(region, nullptr, nullptr); }
CullResult PublishedShadowShrinking::cull_region_carrying(const ViewRegion& region, const std::vector<char>& known,
                                                          const std::vector<char>* known_passive) {
  return sweep(region, &known, known_passive);
}
CullResult PublishedShadowShrinking::sweep(const ViewRegion& region, const std::vector<char>* known,
                                           const std::vector<char>* known_passive) {
  return sweep_region(scene_, quadtree_, horizon_, region,
                      [&](ShadowQueue& pending, std::uint32_t index, Vec3 eye, double distance, double unclipped,
                          const std::vector<std::optional<ConvexSpan>>& spans) {
                        const Building& building = scene_.buildings[index];
                        const Vec2 e = plan(eye);
                        const bool may_be_clipped = distance < unclipped;
                        for (std::size_t p = 0; p < building.prisms.size(); ++p) {
                          const ConvexVerticalPrism& prism = building.prisms[p];
                          if (!spans[p] || (may_be_clipped && min_boundary_distance(prism.ring, e) < unclipped)) continue;
                          if (!corrected_) {
                            const auto shadow = published_shrunk_shadow(prism, eye, *spans[p], region.radius);
                            const double farthest = max_vertex_distance(prism.ring, e);
                            if (shadow && usable_shadow(farthest, shadow->slope)) pending.push(farthest, shadow->span, shadow->slope);
                          } else if (const auto shadow = corrected_shrunk_shadow(prism, eye, *spans[p], region.radius)) {
                            const double farthest = max_vertex_distance(prism.ring, e) + 2 * region.radius;
                            if (usable_shadow(farthest, shadow->slope)) pending.push(farthest, shadow->span, shadow->slope);
                          }
                        }
                      },
                      known, passive_ ? &*passive_ : nullptr, known_passive,
                      // The published variant keeps the centre's near-plane guard: the thesis's
                      // equations know no near plane, and every eye's guard would drop a wall
                      // crossing the disc as an occluder, hiding the ledger's refutation of
                      // Eq. 4-5 behind a rule of ours (kept case slab_across_the_disc).
                      /*guard_every_eye=*/corrected_, /*cast_reads_spans=*/true, /*narrow_targets=*/narrow_targets_);
}

// Wonka et al.'s shrinking as ch. 4.1.1 describes it: each CVP's footprint moved inward by ε
// (preshrunk_occluders.hpp says why that holds for the disc).
std::vector<ConvexVerticalPrism> FootprintShrinking::shrink(std::size_t b, double epsilon) {
  std::vector<ConvexVerticalPrism> out;
  for (const ConvexVerticalPrism& prism : scene_.buildings[b].prisms)
    if (auto ring = shrink_convex_ring(prism.ring, epsilon)) out.push_back({std::move(*ring), prism.height});
  return out;
}

std::optional<std::vector<Vec2>> shrink_convex_ring(const std::vector<Vec2>& ring, double by) {
  // Clip the ring by each edge's half-plane moved inward by `by` (Sutherland-Hodgman; a convex
  // ring stays convex and counter-clockwise).
  std::vector<Vec2> out = ring, next;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 a = ring[j], d = ring[i] - ring[j];
    const double len = length(d);
    if (len == 0.0) continue;
    const Vec2 inward{-d.y / len, d.x / len};  // left of a counter-clockwise edge is inside
    auto depth = [&](Vec2 p) { return dot(p - a, inward) - by; };  // >= 0: kept
    next.clear();
    for (std::size_t k = 0, m = out.size(); k < m; ++k) {
      const Vec2 p = out[k], q = out[(k + 1) % m];
      const double dp = depth(p), dq = depth(q);
      if (dp >= 0.0) next.push_back(p);
      if ((dp >= 0.0) != (dq >= 0.0)) next.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    out.swap(next);
    if (out.size() < 3) return std::nullopt;
  }
  // Drop a sliver: every edge of what is left must have some length and area must be positive.
  double area = 0.0;
  for (std::size_t k = 0, m = out.size(); k < m; ++k) area += cross(out[k], out[(k + 1) % m]);
  if (!(area > 1e-12)) return std::nullopt;
  return out;
}

CertifiedShadowShrinking::CertifiedShadowShrinking(const Scene& scene, const MethodOptions& options, bool narrow_targets)
    : scene_(scene),
      quadtree_(scene, options.quadtree_leaf_size),
      certificate_(scene, quadtree_, options.horizon_bins),
      narrow_targets_(narrow_targets) {}

// The PVS: every building the certificate could not mark hidden (certainly visible or
// uncertain); buildings certainly outside every view volume of the region are not in it.
CullResult CertifiedShadowShrinking::cull_region(const ViewRegion& region) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  certificate_.certify(MotionRegion{region.camera, region.radius, 0.0, region.turn}, result.stats, /*same_as_oh_os=*/false,
                       narrow_targets_);
  for (std::uint32_t b : certificate_.visible()) result.pvs.push_back(scene_.buildings[b].id);
  for (std::uint32_t b : certificate_.swept())
    if (!certificate_.certainly_visible(b)) result.pvs.push_back(scene_.buildings[b].id);
  std::sort(result.pvs.begin(), result.pvs.end());
  result.stats.cull_ms = ms_since(start);
  return result;
}

}  // namespace cullcheck
