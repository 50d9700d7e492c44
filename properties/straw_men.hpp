// Straw-man culling methods, for tests only (conventions: "Prove the tests' power"): each is
// wrong in one way a property must catch, and the tests assert that the property rejects it.
//  - FrustumPvsAsHorizon returns the frustum PVS while posing as oh_os_conservative: it is
//    conservative, so only a precision check (over-estimation against the oracle, culling beyond
//    the frustum in occluded scenes) can reject it;
//  - EverythingStrawMan returns every building while posing as frustum culling: conservative
//    too, and rejected the same way;
//  - DropsOneVisibleBuilding returns oh_os_conservative's PVS less one building that a denser
//    oracle than the properties' sees (the farthest such: small on screen, the hardest for the
//    properties' oracle to witness), so the conservativeness check must catch it.
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "engine/method.hpp"
#include "oracle/oracle.hpp"

namespace cullcheck {

// The name of the method whose claims a straw man poses with (precision_claims.hpp).
class StrawMan : public CullingMethod {
 public:
  explicit StrawMan(std::string poses_as) : poses_as_(std::move(poses_as)) {}
  bool claims_conservative() const override { return true; }
  const std::string& poses_as() const { return poses_as_; }

 private:
  std::string poses_as_;
};

class FrustumPvsAsHorizon final : public StrawMan {
 public:
  FrustumPvsAsHorizon(const Scene& scene, const MethodOptions& options)
      : StrawMan("oh_os_conservative"), frustum_(make_method("frustum", scene, options)) {}
  std::string name() const override { return "straw_frustum_as_horizon"; }
  CullResult cull(const Camera& camera) override { return frustum_->cull(camera); }

 private:
  std::unique_ptr<CullingMethod> frustum_;
};

class EverythingStrawMan final : public StrawMan {
 public:
  explicit EverythingStrawMan(const Scene& scene) : StrawMan("frustum") {
    for (const Building& b : scene.buildings) all_.push_back(b.id);
    std::sort(all_.begin(), all_.end());
  }
  std::string name() const override { return "straw_everything"; }
  std::string unsupported_camera(const Camera& /*camera*/) const override { return ""; }
  CullResult cull(const Camera& /*camera*/) override { return {all_, {}, {}}; }

 private:
  std::vector<ObjectId> all_;
};

// The denser oracle it cheats with: 1.5 m sample spacing, 256 stratified columns (the
// properties' is 3 m and 128, property_oracle.hpp).
inline oracle::OracleOptions denser_oracle() {
  oracle::OracleOptions o;
  o.sampling.spacing_m = 1.5;
  o.sampling.frustum_resolution = 256;
  o.sampling.threads = 1;
  return o;
}

class DropsOneVisibleBuilding final : public StrawMan {
 public:
  DropsOneVisibleBuilding(const Scene& scene, const MethodOptions& options)
      : StrawMan("oh_os_conservative"), scene_(scene), horizon_(make_method("oh_os_conservative", scene, options)), truth_(scene) {}
  std::string name() const override { return "straw_drops_one_visible"; }
  CullResult cull(const Camera& camera) override {
    CullResult r = horizon_->cull(camera);
    const std::vector<ObjectId> seen = truth_.visible_set(camera, denser_oracle()).visible;
    double farthest = -1.0;
    dropped_.reset();
    for (const Building& b : scene_.buildings) {
      if (!std::binary_search(seen.begin(), seen.end(), b.id) || !std::binary_search(r.pvs.begin(), r.pvs.end(), b.id)) continue;
      const Vec2 centre{(b.bounds.lo.x + b.bounds.hi.x) / 2, (b.bounds.lo.y + b.bounds.hi.y) / 2};
      const double d = length(centre - plan(camera.position));
      if (d > farthest) farthest = d, dropped_ = b.id;
    }
    if (dropped_) r.pvs.erase(std::lower_bound(r.pvs.begin(), r.pvs.end(), *dropped_));
    return r;
  }
  // The building the last cull() dropped (none when the denser oracle saw nothing it kept).
  std::optional<ObjectId> dropped() const { return dropped_; }

 private:
  const Scene& scene_;
  std::unique_ptr<CullingMethod> horizon_;
  oracle::Oracle truth_;
  std::optional<ObjectId> dropped_;
};

}  // namespace cullcheck
