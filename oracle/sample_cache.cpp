#include "oracle/sample_cache.hpp"

namespace cullcheck::oracle {

struct SampleCache::Table {
  std::vector<std::atomic<const SurfaceSamples*>> objects;
  explicit Table(std::size_t n) : objects(n) {}
  ~Table() {
    for (auto& o : objects) delete o.load(std::memory_order_relaxed);
  }
};

SampleCache::SampleCache(const Scene& scene, const TriangleMesh& mesh, std::size_t budget_points)
    : scene_(scene), mesh_(mesh), budget_points_(budget_points) {}

SampleCache::~SampleCache() = default;

SampleCache::AtDensity SampleCache::at(const SamplingOptions& o) {
  const Density key{o.spacing_m, o.face_grid, o.edge_samples, o.inset, o.max_samples_per_building};
  const std::lock_guard<std::mutex> lock(tables_mutex_);
  std::unique_ptr<Table>& t = tables_[key];
  if (!t) t = std::make_unique<Table>(scene_.object_count());
  return AtDensity(*this, *t, o);
}

void sample_object(const Scene& scene, const TriangleMesh& mesh, std::uint32_t index, const SamplingOptions& options,
                   SurfaceSamples& out) {
  if (index < scene.buildings.size())
    surface_samples(scene.buildings[index], mesh.roofs[index], options, out);
  else
    surface_samples(scene.meshes[index - scene.buildings.size()], options, out);
}

const SurfaceSamples& SampleCache::AtDensity::samples(std::uint32_t index, SurfaceSamples& scratch) const {
  std::atomic<const SurfaceSamples*>& slot = table_.objects[index];
  if (const SurfaceSamples* kept = slot.load(std::memory_order_acquire)) return *kept;
  sample_object(cache_.scene_, cache_.mesh_, index, options_, scratch);
  std::atomic<std::size_t>& kept_points = cache_.points_kept_;
  const std::size_t n = scratch.points.size();
  // Reserve the points against the budget first, so that concurrent askers cannot overshoot it.
  if (kept_points.fetch_add(n, std::memory_order_relaxed) + n > cache_.budget_points_) {
    kept_points.fetch_sub(n, std::memory_order_relaxed);
    return scratch;
  }
  auto kept = std::make_unique<SurfaceSamples>(scratch);
  kept->points.shrink_to_fit();
  const SurfaceSamples* expected = nullptr;
  if (slot.compare_exchange_strong(expected, kept.get(), std::memory_order_acq_rel)) return *kept.release();
  kept_points.fetch_sub(n, std::memory_order_relaxed);  // another thread kept the same points first
  return *expected;
}

}  // namespace cullcheck::oracle
