// The one interface every culling method implements (conventions: "a thin, plain API").
//
// A method is built once for a scene (its preprocessing: quadtree, occluder lists, ...) and then
// answers queries: a camera in, a potentially visible set (PVS: sorted building ids) and
// statistics out. The CLI, the properties and the reports all go through this interface.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"

namespace cullcheck {

struct CullStatistics {
  std::uint64_t cells_tested = 0;       // quadtree cells tested against frustum / horizon
  std::uint64_t buildings_tested = 0;   // buildings tested individually
  std::uint64_t horizon_nodes = 0;      // horizon tree nodes visited (queries + updates)
  std::uint64_t occluders_applied = 0;  // CVP shadows merged into the horizon
  double cull_ms = 0.0;                 // wall time of this query
};

struct CullResult {
  std::vector<ObjectId> pvs;  // sorted ascending, no duplicates
  CullStatistics stats;
};

class CullingMethod {
 public:
  virtual ~CullingMethod() = default;
  // Stable name used in reports and on the command line, e.g. "oh_os_conservative".
  virtual std::string name() const = 0;
  // Whether the method claims oracle-witnessed ⊆ PVS (the property and CI gate enforce it).
  virtual bool claims_conservative() const = 0;
  virtual CullResult cull(const Camera& camera) = 0;
};

struct MethodOptions {
  std::uint32_t horizon_bins = 4096;  // azimuth resolution of the occlusion horizon over 2*pi
  std::uint32_t quadtree_leaf_size = 8;  // max buildings per quadtree leaf
};

// Names accepted by make_method, in report order.
std::vector<std::string> method_names();
// Throws std::invalid_argument naming the method when it is unknown.
std::unique_ptr<CullingMethod> make_method(std::string_view name, const Scene& scene, const MethodOptions& options = {});

}  // namespace cullcheck
