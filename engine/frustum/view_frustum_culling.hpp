// View-frustum culling with the six-plane test (the baseline every other method is compared
// with). Claim: conservative — a building is dropped only when its bounding box lies entirely
// outside one plane of the view volume (or beyond `far` in 360-degree mode). Cells of the
// quadtree are tested first so that whole districts are dropped at once.
#pragma once

#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

class ViewFrustumCulling final : public CullingMethod {
 public:
  explicit ViewFrustumCulling(const Scene& scene, const MethodOptions& options = {});
  std::string name() const override { return "frustum"; }
  bool claims_conservative() const override { return true; }
  std::string unsupported_camera(const Camera& /*camera*/) const override { return ""; }
  CullResult cull(const Camera& camera) override;

 private:
  const Scene& scene_;
  Quadtree quadtree_;
};

}  // namespace cullcheck
