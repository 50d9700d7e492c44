// From-region PVS by occluder-shadow shrinking (thesis ch. 4.1.2, "adjustable shrinking"): a PVS
// computed at a point that holds for every viewpoint of the ε-disc around it (ViewRegion).
//
// Four variants over the same front-to-back sweep as OH(OS):
//  - shrink_adjustable_thesis — as published. Buildings are tested from the disc's centre as in
//    OH(OS) (the published shadow rule, β_min from the two tangent vertices); each visible CVP's
//    shadow is shrunk before it enters the horizon: horizontally by Eq. 4-6, α_max - asin(ε/|AC|)
//    and α_min + asin(ε/|CE|) for the tangent vertices A (at α_max) and E (at α_min); vertically by
//    Eq. 9-12 for occluders taller than the eye (β_s = atan((ε + d)/(h_X - h_C)) - atan(d/(h_X -
//    h_C))) and Eq. 13-14 for lower ones (β_F = atan(d/(h_C + h_X)), β_N = atan((d - ε)/(h_C +
//    h_X)), with h_C + h_X as printed), β_min,s = β_min - β_s, d the distance of the vertex that
//    gives β_min. The view volume is widened to the union of the region's (Fig. 4.8 f2/f3).
//    Claim (as published): conservative for the disc. Held to the oracle in
//    properties/region_shrinking_test.cpp.
//  - shrink_former — Wonka et al.'s occluder shrinking as ch. 4.1.1 describes it: every CVP's
//    footprint moved inward by ε beforehand (so occluders thinner than 2ε vanish and sharp
//    corners over-shrink, Fig. 4.3), shadows with OH(OS)'s conservative rule, the eye's height
//    fixed. A non-convex footprint is shrunk CVP by CVP, which also moves the edges between its
//    CVPs: more shrinking than the footprint's own offset, so never less conservative.
//  - shrink_adjustable_conservative — the bounds the guarded ΔH proves (engine/delta_horizon/
//    motion_region.hpp, with no vertical motion): the PVS is every building that may meet some
//    camera's view volume and that is not hidden, for every camera of the region, behind the
//    shadows of the buildings swept (each shrunk for the region: span narrowed by asin(ε / r)
//    per tangent vertex, elevation lowered, merged only beyond the CVP's farthest point + 2ε);
//    conservative wherever OH(OS)'s shadows are. A building or cell is tested by its span
//    narrowed by asin(ε / its farthest distance) (target_span, engine/horizon/horizon_sweep.hpp),
//    not widened as for OH(OS)'s decision at every eye: what it holds is what some eye sees, which
//    can be less than OH(OS)'s PVS at that eye.
//  - shrink_adjustable_corrected — the published method with what the oracle refuted replaced
//    (see PublishedShadowShrinking below).
// The Minkowski mesh shrinking of the slice-wise paper is in minkowski_shrinking.hpp.
#pragma once

#include <optional>
#include <vector>

#include "engine/delta_horizon/motion_region.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/method.hpp"
#include "engine/shrinking/passive_targets.hpp"
#include "engine/shrinking/preshrunk_occluders.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

// `corrected`: shrink_adjustable_corrected — the published method with the three things the oracle
// refuted replaced (properties/region_extremes_test.cpp, the claims ledger): OH(OS)'s conservative
// shadow rule instead of the published β_min; the vertical shrink as the sight line over the
// shadow's edge from the disc's farthest (taller than the eye: slope r / (d + ε)) or nearest
// (lower: r / (d - ε), no shadow when d <= ε) point, which is Eq. 9-12 unchanged and Eq. 13-14
// with the geometry's h_C - h_X where the thesis prints h_C + h_X; and each shadow merged only
// once the sweep is 2ε beyond the CVP's farthest point (a disc viewpoint may meet things in
// another order); a CVP that comes within ε of the centre casts no shadow (the published method
// drops only those whose tangent vertices do). Buildings and cells are tested by their spans
// narrowed by asin(ε / farthest distance) (target_span, engine/horizon/horizon_sweep.hpp): the
// umbra's edge is a line, not the azimuth the shadow is narrowed to, and a target short of
// infinity lies that far inside it (on Table 4.1's walk, +25% over the point PVS without it,
// +11% with it). Not proven: the claims ledger and the oracle properties decide
// (region_extremes_test's TargetAtTheEdgeOfTheUmbra pins the edge).
class PublishedShadowShrinking final : public RegionCullingMethod {
 public:
  // `narrow_targets` (the corrected variant only): false tests targets by their whole spans, as
  // before target_span (kept so that tests can count the buildings the narrowing decides).
  PublishedShadowShrinking(const Scene& scene, const MethodOptions& options = {}, bool corrected = false,
                           bool narrow_targets = true);
  std::string name() const override { return corrected_ ? "shrink_adjustable_corrected" : "shrink_adjustable_thesis"; }
  bool claims_conservative() const override { return corrected_; }
  CullResult cull_region(const ViewRegion& region) override;
  CullResult cull_region_carrying(const ViewRegion& region, const std::vector<char>& known,
                                  const std::vector<char>* known_passive = nullptr) override;
  bool carries_known() const override { return true; }
  bool supports_passive_targets() const override { return true; }
  void set_passive_targets(const Scene& targets) override { passive_.emplace(targets, options_); }

 private:
  CullResult sweep(const ViewRegion& region, const std::vector<char>* known, const std::vector<char>* known_passive);

  const Scene& scene_;
  MethodOptions options_;
  Quadtree quadtree_;
  OcclusionHorizon horizon_;
  bool corrected_;
  std::optional<PassiveTargets> passive_;
  bool narrow_targets_;
};

class FootprintShrinking final : public PreshrunkOccluders {
 public:
  FootprintShrinking(const Scene& scene, const MethodOptions& options = {}) : PreshrunkOccluders(scene, options) {}
  std::string name() const override { return "shrink_former"; }
  bool claims_conservative() const override { return true; }

 private:
  std::vector<ConvexVerticalPrism> shrink(std::size_t b, double epsilon) override;
};

// A convex counter-clockwise ring with every edge moved inward by `by`; empty when nothing is
// left (an occluder thinner than 2 * by disappears).
std::optional<std::vector<Vec2>> shrink_convex_ring(const std::vector<Vec2>& ring, double by);

class CertifiedShadowShrinking final : public RegionCullingMethod {
 public:
  // `narrow_targets`: as PublishedShadowShrinking's (RegionCertificate::certify).
  CertifiedShadowShrinking(const Scene& scene, const MethodOptions& options = {}, bool narrow_targets = true);
  std::string name() const override { return "shrink_adjustable_conservative"; }
  bool claims_conservative() const override { return true; }
  CullResult cull_region(const ViewRegion& region) override;

 private:
  const Scene& scene_;
  Quadtree quadtree_;
  RegionCertificate certificate_;
  bool narrow_targets_;
};

}  // namespace cullcheck
