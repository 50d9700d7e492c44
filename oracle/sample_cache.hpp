// Every object's surface samples (surface_samples.hpp), computed once and kept across queries.
//
// Samples depend on the object and the sampling density only, never on the camera, so a walk of
// hundreds of frames over one city would otherwise sample the same candidates again at every
// frame (most of the ray plan's time besides the rays themselves). Kept per density (the fields
// of SamplingOptions the samples depend on), filled the first time a query asks for an object, up
// to a budget of points; past it, objects are sampled afresh into the caller's scratch, as before.
//
// Thread-safe: units of one query (and concurrent queries) may ask at once. Two threads asking
// for the same object both sample it; one copy is kept, and both are the same points.
#pragma once

#include <atomic>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <vector>

#include "core/scene.hpp"
#include "oracle/mesh.hpp"
#include "oracle/sampling.hpp"
#include "oracle/surface_samples.hpp"

namespace cullcheck::oracle {

// Object `index`'s samples (mesh.hpp's order: buildings with the oracle's roof triangles, then
// mesh objects) into `out`, computed afresh.
void sample_object(const Scene& scene, const TriangleMesh& mesh, std::uint32_t index, const SamplingOptions& options,
                   SurfaceSamples& out);

class SampleCache {
 public:
  // 2^23 points (200 MB) by default: every building of the CLI's default city at the default
  // density is 2.4 M points (58 MB).
  static constexpr std::size_t kDefaultBudgetPoints = std::size_t(1) << 23;

  SampleCache(const Scene& scene, const TriangleMesh& mesh, std::size_t budget_points = kDefaultBudgetPoints);
  ~SampleCache();
  SampleCache(const SampleCache&) = delete;
  SampleCache& operator=(const SampleCache&) = delete;

  struct Table;
  // The samples kept at one density: looked up once per query, then asked once per object.
  class AtDensity {
   public:
    // Object `index`'s samples (mesh.hpp's order: buildings, then mesh objects): the kept ones,
    // or, past the budget, `scratch` filled afresh.
    const SurfaceSamples& samples(std::uint32_t index, SurfaceSamples& scratch) const;

   private:
    friend class SampleCache;
    AtDensity(SampleCache& cache, Table& table, const SamplingOptions& options) : cache_(cache), table_(table), options_(options) {}
    SampleCache& cache_;
    Table& table_;
    const SamplingOptions& options_;
  };
  AtDensity at(const SamplingOptions& options);
  std::size_t points_kept() const { return points_kept_.load(std::memory_order_relaxed); }

 private:
  // What the samples depend on: spacing, face grid, edge samples, inset, the per-object cap.
  using Density = std::tuple<double, int, int, double, std::size_t>;

  const Scene& scene_;
  const TriangleMesh& mesh_;
  const std::size_t budget_points_;
  std::atomic<std::size_t> points_kept_{0};
  std::mutex tables_mutex_;
  std::map<Density, std::unique_ptr<Table>> tables_;
};

}  // namespace cullcheck::oracle
