#include "engine/method.hpp"

#include <stdexcept>

#include "engine/frustum/view_frustum_culling.hpp"
#include "engine/horizon/object_space_horizon.hpp"

namespace cullcheck {

std::vector<std::string> method_names() { return {"frustum", "oh_os_thesis", "oh_os_conservative"}; }

std::unique_ptr<CullingMethod> make_method(std::string_view name, const Scene& scene, const MethodOptions& options) {
  if (name == "frustum") return std::make_unique<ViewFrustumCulling>(scene, options);
  if (name == "oh_os_thesis") return std::make_unique<ObjectSpaceHorizonCulling>(scene, ShadowRule::thesis, options);
  if (name == "oh_os_conservative")
    return std::make_unique<ObjectSpaceHorizonCulling>(scene, ShadowRule::conservative, options);
  std::string known;
  for (const auto& n : method_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown method '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace cullcheck
