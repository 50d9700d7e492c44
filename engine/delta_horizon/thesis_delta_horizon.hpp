// The incremental occlusion horizon ΔH exactly as published (thesis ch. 3.1.3, steps 1-5 and
// Fig. 3.8), without a guard: the variant that Fig. 3.10's lateral-movement failure applies to.
//
// Frame t leaves H(t) (every visible building's shadow merged) and the buildings tested at t
// ("the cells in front of H(t)", one building per cell as in the thesis's testbed). Frame t+1:
//  2) H(t+1) is built from those buildings alone, front to back, with OH(OS)'s tests and its
//     rule of merging a shadow once the sweep has passed the CVP's farthest point;
//  3) ΔH = H(t+1) - H(t) bin by bin: where H rose, ΔH is +inf ("no need to check the cells
//     behind ... they have already occluded in frame t"); where it fell (the openings), ΔH
//     copies H(t+1);
//  4) the quadtree is swept front to back against ΔH: cells and buildings that project into
//     the openings are tested, new visible buildings join the PVS and raise H(t+1) and ΔH;
//  5) bins that were outside the view at t start at +inf in H(t), so after a turn they are
//     openings and what entered the view is tested.
// Representation: the horizon is OH(OS)'s (bins in blocks with block min/max and lazy raises);
// ΔH is computed by one pass over the bins, which is what the thesis's linked list is for.
//
// Claim (as published): conservative, like OH(OS). cullcheck refutes it (the lateral fuzzer in
// properties/ finds and shrinks a counterexample; the claims ledger records it), so this variant
// reports claims_conservative() == false and is not gated; delta_h_guarded is the fix.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

class ThesisDeltaHorizonCulling final : public CullingMethod {
 public:
  ThesisDeltaHorizonCulling(const Scene& scene, const MethodOptions& options = {});
  std::string name() const override { return "delta_h_thesis"; }
  bool claims_conservative() const override { return false; }
  bool incremental() const override { return true; }
  CullResult cull(const Camera& camera) override;

  // H(t) as left by the last query.
  OcclusionHorizon& horizon() { return horizon_; }

 private:
  const Scene& scene_;
  Quadtree quadtree_;
  OcclusionHorizon horizon_, delta_;
  std::vector<double> previous_;           // H(t) bin by bin; empty before the first frame
  std::vector<std::uint32_t> front_;       // buildings tested at t
  std::vector<std::uint32_t> tested_at_;   // per building: frame stamp when tested this frame
  std::uint32_t frame_ = 0;
};

}  // namespace cullcheck
