// Guarded incremental occlusion horizon, ΔH (thesis ch. 3.1.3, with the guard that Fig. 3.10
// calls for; see motion_region.hpp for the guard and why the published method needs one).
//
// Claim: from a point, 6 DoF, up to 360 degrees, the same PVS and the same final horizon as full
// OH(OS) with the conservative shadow rule, at every frame, whatever the camera path; so it is
// conservative wherever OH(OS) is. Frame-to-frame coherence is used as follows:
//  - H(t) carried over: a horizon of occluder shadows shrunk for a motion region around an
//    anchor camera marks the cells and buildings hidden from every camera of that region;
//  - each frame inside the region builds H(t+1) front to back exactly as OH(OS) does, but never
//    tests a marked item (the steps "skip what lies behind the risen parts" and "test only the
//    cells in the openings", with the skip proven rather than assumed);
//  - a camera outside the region (moved more than `delta_radius`/`delta_height`, turned more
//    than `delta_turn`, other field of view or clip planes) re-anchors the region at itself:
//    the guard fires, and the frame costs a certificate sweep on top of its own.
// Statistics: items_skipped counts marked items not tested; guard_fires is 1 on re-anchoring.
#pragma once

#include <optional>

#include "engine/delta_horizon/motion_region.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

class GuardedDeltaHorizonCulling final : public CullingMethod {
 public:
  GuardedDeltaHorizonCulling(const Scene& scene, const MethodOptions& options = {});
  std::string name() const override { return "delta_h_guarded"; }
  bool claims_conservative() const override { return true; }
  CullResult cull(const Camera& camera) override;

  // The horizon H(t) as left by the last query (every visible building's shadows merged).
  OcclusionHorizon& horizon() { return horizon_; }
  const HiddenCertificate& certificate() const { return certificate_; }

 private:
  const Scene& scene_;
  MethodOptions options_;
  Quadtree quadtree_;
  OcclusionHorizon horizon_, shrunk_;
  HiddenCertificate certificate_;
  std::optional<MotionRegion> region_;
};

}  // namespace cullcheck
