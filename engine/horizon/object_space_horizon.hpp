// Full object-space occlusion horizon culling, OH(OS) (thesis ch. 3.1.2).
//
// Claim (as published): conservative from a point, 6 DoF, up to 360 degrees.
//
// Per query, one front-to-back sweep of the quadtree against the horizon (horizon_sweep.hpp says
// how, and what the PVS is independent of traversal order). A CVP that may reach in front of the
// near plane is not used as an occluder: the clipped part hides nothing.
//
// The shadow of a CVP is one elevation over its azimuth span (ch. 3.1.2, Fig. 3.4). Which
// elevation is the variant:
//  - ShadowRule::thesis — as published: the smaller elevation of the two extreme-azimuth
//    (tangent) vertices' tops.
//  - ShadowRule::conservative — the lowest elevation of the prism's silhouette over the span.
//    For a roof at or above the eye the silhouette is the near chain's top, whose farthest point
//    is a tangent vertex, so this equals the thesis value. For a roof below the eye the
//    silhouette is the far chain's top; its nearest point can lie between the tangents (a wide
//    low roof seen from above), where the thesis value is too high and hides what shows above
//    the roof's far edge. Here the bound uses the distance to the far chain instead.
#pragma once

#include <memory>

#include "engine/horizon/horizon_sweep.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/horizon/polar_geometry.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

class ObjectSpaceHorizonCulling final : public CullingMethod {
 public:
  ObjectSpaceHorizonCulling(const Scene& scene, ShadowRule rule, const MethodOptions& options = {});
  std::string name() const override;
  // The thesis claims conservativeness for its rule too, but cullcheck's claims ledger refutes
  // it (see above), so only the corrected variant is held to the gate.
  bool claims_conservative() const override { return rule_ == ShadowRule::conservative; }
  CullResult cull(const Camera& camera) override;
  const Quadtree* swept_quadtree() const override { return &quadtree_; }

  // The horizon as left by the last query (for invariants, reports and the ΔH method).
  OcclusionHorizon& horizon() { return horizon_; }
  const Quadtree& quadtree() const { return quadtree_; }

 private:
  const Scene& scene_;
  ShadowRule rule_;
  Quadtree quadtree_;
  OcclusionHorizon horizon_;
};

}  // namespace cullcheck
