// Polar-diagram visibility as a culling method (Ortega, Rueda and Feito): the buildings the
// plan-view fan of rays (visibility_fan.hpp) sees from the eye over the camera's horizontal
// field of view.
//
// The plan view is the true visible set only in the paper's "2.5D city seen from the street":
// a level camera, every building taller than the eye, the eye outside every footprint, near and
// far out of the way, and no building low enough for a rising ray to pass over it and meet a
// taller one behind (the same conditions as the oracle's exact_2d, decided here by the engine's
// own tests). claims_conservative_for says whether a camera meets them; elsewhere the method
// still answers (its PVS can miss what is seen over a building), and the gate does not hold it.
#pragma once

#include <string>
#include <vector>

#include "engine/method.hpp"
#include "engine/polar_diagram/visibility_fan.hpp"

namespace cullcheck {

class PolarDiagramCulling final : public CullingMethod {
 public:
  explicit PolarDiagramCulling(const Scene& scene, polar::FanOptions options = {});
  std::string name() const override { return "polar_diagram"; }
  // Not for every camera (as OH(IS)): claims_conservative_for says where.
  bool claims_conservative() const override { return false; }
  bool claims_conservative_for(const Camera& camera) const override { return plan_view_exact(camera).empty(); }
  std::string unsupported_camera(const Camera& camera) const override;
  CullResult cull(const Camera& camera) override;

  // Why the plan view is not the exact visible set for `camera` (empty when it is).
  std::string plan_view_exact(const Camera& camera) const;
  const polar::VisibilityFan& fan() const { return fan_; }
  const polar::FanStatistics& last_statistics() const { return last_; }

 private:
  const Scene& scene_;
  polar::VisibilityFan fan_;
  polar::FanStatistics last_;
  double lowest_ = 0.0, tallest_ = 0.0;
};

}  // namespace cullcheck
