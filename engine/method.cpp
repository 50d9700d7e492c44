#include "engine/method.hpp"

#include <algorithm>
#include <stdexcept>

#include "engine/delta_horizon/guarded_delta_horizon.hpp"
#include "engine/delta_horizon/thesis_delta_horizon.hpp"
#include "engine/frustum/range_detection.hpp"
#include "engine/frustum/view_frustum_culling.hpp"
#include "engine/horizon/object_space_horizon.hpp"
#include "engine/shrinking/minkowski_shrinking.hpp"
#include "engine/shrinking/region_shrinking.hpp"
#include "engine/image_space/image_space_horizon.hpp"
#include "engine/online_image_space/online_culling.hpp"
#include "engine/polar_diagram/polar_culling.hpp"

namespace cullcheck {
namespace {

std::invalid_argument unknown(std::string_view kind, std::string_view name, const std::vector<std::string>& names) {
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  return std::invalid_argument("unknown " + std::string(kind) + " '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace

std::string CullingMethod::unsupported_camera(const Camera& camera) const {
  if (camera.orthographic())
    return "orthographic camera: " + name() + " builds its horizon from one eye point; only frustum culling and "
           "outside subjects take orthographic cameras";
  return "";
}

std::string method_unavailable_reason(std::string_view name, const Scene& scene) {
  // Frustum culling and on-line image-space culling work on polygons, so on any scene.
  if (name == "frustum" || name == "rdt" || name == "rdt_corrected" || name == "radar_frustum" || name == "online_is" || name == "online_is_guarded" || scene.prisms_only()) return "";
  return "the scene holds " + std::to_string(scene.meshes.size()) + " mesh object(s) that are not vertical prisms; " +
         std::string(name) + " models every object as convex vertical prisms (2.5D), so only the oracle, frustum " +
         "culling and outside subjects run on it";
}

std::vector<std::string> method_names() { return {"frustum", "rdt", "rdt_corrected", "radar_frustum", "oh_is", "oh_os_thesis", "oh_os_conservative", "delta_h_thesis", "delta_h_guarded", "online_is",
                                                 "online_is_guarded", "polar_diagram"}; }

std::unique_ptr<CullingMethod> make_method(std::string_view name, const Scene& scene, const MethodOptions& options) {
  if (const std::string why = method_unavailable_reason(name, scene); !why.empty()) {
    const auto names = method_names();
    if (std::find(names.begin(), names.end(), name) != names.end()) throw std::invalid_argument("method " + std::string(name) + ": " + why);
  }
  if (name == "frustum") return std::make_unique<ViewFrustumCulling>(scene, options);
  if (name == "rdt") return std::make_unique<RangeDetectionCulling>(scene, RangeRule::published, options);
  if (name == "rdt_corrected") return std::make_unique<RangeDetectionCulling>(scene, RangeRule::corrected, options);
  if (name == "radar_frustum") return std::make_unique<RangeDetectionCulling>(scene, RangeRule::radar, options);
  if (name == "oh_is") return std::make_unique<ImageSpaceHorizonCulling>(scene, options);
  if (name == "oh_os_thesis") return std::make_unique<ObjectSpaceHorizonCulling>(scene, ShadowRule::thesis, options);
  if (name == "oh_os_conservative")
    return std::make_unique<ObjectSpaceHorizonCulling>(scene, ShadowRule::conservative, options);
  if (name == "delta_h_thesis") return std::make_unique<ThesisDeltaHorizonCulling>(scene, options);
  if (name == "delta_h_guarded") return std::make_unique<GuardedDeltaHorizonCulling>(scene, options);
  if (name == "online_is")
    return std::make_unique<OnlineImageSpaceCulling>(scene, OnlineImageSpaceCulling::Variant::published, options.online);
  if (name == "online_is_guarded")
    return std::make_unique<OnlineImageSpaceCulling>(scene, OnlineImageSpaceCulling::Variant::guarded, options.online);
  if (name == "polar_diagram") return std::make_unique<PolarDiagramCulling>(scene);
  throw unknown("method", name, method_names());
}

void RegionCullingMethod::set_passive_targets(const Scene& /*targets*/) {
  throw std::invalid_argument("region method '" + name() +
                              "' cannot test passive targets (navigable regions); use one built on the shrinking "
                              "sweep: shrink_former, shrink_adjustable_thesis, shrink_adjustable_corrected, "
                              "shrink_minkowski");
}

std::vector<std::string> region_method_names() {
  return {"shrink_former", "shrink_adjustable_thesis", "shrink_adjustable_conservative", "shrink_minkowski",
          "shrink_adjustable_corrected"};
}

std::unique_ptr<RegionCullingMethod> make_region_method(std::string_view name, const Scene& scene,
                                                        const MethodOptions& options) {
  if (const std::string why = method_unavailable_reason(name, scene); !why.empty()) {
    const auto names = region_method_names();
    if (std::find(names.begin(), names.end(), name) != names.end())
      throw std::invalid_argument("region method " + std::string(name) + ": " + why);
  }
  if (name == "shrink_former") return std::make_unique<FootprintShrinking>(scene, options);
  if (name == "shrink_adjustable_thesis") return std::make_unique<PublishedShadowShrinking>(scene, options);
  if (name == "shrink_adjustable_conservative") return std::make_unique<CertifiedShadowShrinking>(scene, options);
  if (name == "shrink_adjustable_corrected") return std::make_unique<PublishedShadowShrinking>(scene, options, true);
  if (name == "shrink_minkowski") return std::make_unique<MinkowskiShrinking>(scene, options);
  throw unknown("region method", name, region_method_names());
}

}  // namespace cullcheck
