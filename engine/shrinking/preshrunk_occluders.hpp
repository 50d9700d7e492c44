// The from-region methods that shrink occluders in a preprocessing step (shrink_former,
// shrink_minkowski): each building's shrunk CVPs are computed once per ε and cached, and every
// query is region_sweep.hpp's sweep from the disc's centre, buildings tested unshrunk, shadows
// cast by the shrunk CVPs with OH(OS)'s conservative rule. Why that holds for the whole disc
// (Wonka et al.; slice paper Theorem 1): a sight line from the centre C to a point p that passes
// through a shrunk CVP at q, and the sight line from any eye within ε of C (same height) to p, are
// at the same height at the same fraction of the way and at most ε apart in plan there; a CVP
// shrunk so that it grown by ε stays inside the building therefore blocks the latter too.
#pragma once

#include <optional>
#include <vector>

#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/method.hpp"
#include "engine/shrinking/passive_targets.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

class PreshrunkOccluders : public RegionCullingMethod {
 public:
  CullResult cull_region(const ViewRegion& region) override { return sweep(region, nullptr, nullptr); }
  CullResult cull_region_carrying(const ViewRegion& region, const std::vector<char>& known,
                                  const std::vector<char>* known_passive = nullptr) override {
    return sweep(region, &known, known_passive);
  }
  bool carries_known() const override { return true; }
  bool supports_passive_targets() const override { return true; }
  void set_passive_targets(const Scene& targets) override { passive_.emplace(targets, options_); }

 protected:
  PreshrunkOccluders(const Scene& scene, const MethodOptions& options);
  // The occluders of scene.buildings[b] shrunk by `epsilon` (none: it occludes nothing). Called
  // for every building, in order, when a query brings a new ε.
  virtual std::vector<ConvexVerticalPrism> shrink(std::size_t b, double epsilon) = 0;
  // Called before the shrink() calls of a new ε (a method's per-ε counters start here).
  virtual void begin_shrinking(double /*epsilon*/) {}

  const Scene& scene_;

 private:
  CullResult sweep(const ViewRegion& region, const std::vector<char>* known, const std::vector<char>* known_passive);

  MethodOptions options_;
  Quadtree quadtree_;
  OcclusionHorizon horizon_;
  std::optional<double> shrunk_radius_;
  std::vector<std::vector<ConvexVerticalPrism>> shrunk_;  // per building: its shrunk CVPs
  std::optional<PassiveTargets> passive_;
};

}  // namespace cullcheck
