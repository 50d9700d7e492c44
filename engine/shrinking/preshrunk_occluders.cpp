#include "engine/shrinking/preshrunk_occluders.hpp"

#include "engine/shrinking/region_sweep.hpp"

namespace cullcheck {

PreshrunkOccluders::PreshrunkOccluders(const Scene& scene, const MethodOptions& options)
    : scene_(scene), options_(options), quadtree_(scene, options.quadtree_leaf_size), horizon_(options.horizon_bins) {}

CullResult PreshrunkOccluders::sweep(const ViewRegion& region, const std::vector<char>* known,
                                     const std::vector<char>* known_passive) {
  if (!shrunk_radius_ || *shrunk_radius_ != region.radius) {
    begin_shrinking(region.radius);
    shrunk_.assign(scene_.buildings.size(), {});
    for (std::size_t b = 0; b < scene_.buildings.size(); ++b) shrunk_[b] = shrink(b, region.radius);
    shrunk_radius_ = region.radius;
  }
  return sweep_region(scene_, quadtree_, horizon_, region,
                      [&](ShadowQueue& pending, std::uint32_t index, Vec3 eye, double distance, double unclipped,
                          const std::vector<std::optional<ConvexSpan>>&) {
                        queue_shrunk_shadows(pending, shrunk_[index], eye, distance, unclipped);
                      },
                      known, passive_ ? &*passive_ : nullptr, known_passive, /*guard_every_eye=*/true,
                      /*cast_reads_spans=*/false);
}

}  // namespace cullcheck
