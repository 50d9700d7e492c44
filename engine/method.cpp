#include "engine/method.hpp"

#include <stdexcept>

#include "engine/delta_horizon/guarded_delta_horizon.hpp"
#include "engine/delta_horizon/thesis_delta_horizon.hpp"
#include "engine/frustum/view_frustum_culling.hpp"
#include "engine/horizon/object_space_horizon.hpp"
#include "engine/image_space/image_space_horizon.hpp"

namespace cullcheck {

std::vector<std::string> method_names() { return {"frustum", "oh_is", "oh_os_thesis", "oh_os_conservative", "delta_h_thesis", "delta_h_guarded"}; }

std::unique_ptr<CullingMethod> make_method(std::string_view name, const Scene& scene, const MethodOptions& options) {
  if (name == "frustum") return std::make_unique<ViewFrustumCulling>(scene, options);
  if (name == "oh_is") return std::make_unique<ImageSpaceHorizonCulling>(scene, options);
  if (name == "oh_os_thesis") return std::make_unique<ObjectSpaceHorizonCulling>(scene, ShadowRule::thesis, options);
  if (name == "oh_os_conservative")
    return std::make_unique<ObjectSpaceHorizonCulling>(scene, ShadowRule::conservative, options);
  if (name == "delta_h_thesis") return std::make_unique<ThesisDeltaHorizonCulling>(scene, options);
  if (name == "delta_h_guarded") return std::make_unique<GuardedDeltaHorizonCulling>(scene, options);
  std::string known;
  for (const auto& n : method_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown method '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace cullcheck
