#include "oracle/ray_oracle.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "core/errors.hpp"
#include "oracle/embree_scene.hpp"
#include "oracle/ray_plan.hpp"
#include "oracle/view_transform.hpp"

namespace cullcheck::oracle {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

struct RayOracle::Impl {
  const Scene& scene;
  EmbreeScene embree;

  explicit Impl(const Scene& s) : scene(s), embree(s) {}
};

RayOracle::RayOracle(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
RayOracle::~RayOracle() = default;
const TriangleMesh& RayOracle::mesh() const { return impl_->embree.mesh(); }
const Scene& RayOracle::scene() const { return impl_->scene; }
const EmbreeScene& RayOracle::embree() const { return impl_->embree; }

OracleResult RayOracle::witness(const Camera& camera, const SamplingOptions& options, RayLog* log,
                                TriangleWitnesses* triangles) const {
  const auto start = Clock::now();
  validate(camera);
  validate(options);
  const Impl& im = *impl_;
  const TriangleMesh& mesh = im.embree.mesh();
  OracleResult result;
  result.density = options;
  RayPlan plan(im.scene, mesh, camera, options);
  const ViewTransform& volume = plan.cone().transform();
  auto embree_ray_of = [&](const PlannedRay& r) { return to_float(r.origin - mesh.origin, r.direction, r.t_near, r.t_far); };

  // Chunk by chunk, in plan order: cast the chunk (each thread takes blocks and writes hits at
  // the rays' own indices), then merge it in ray order. An object is witnessed by the first
  // ray whose first hit lies on it and inside the view volume, whatever the thread count.
  constexpr std::size_t kChunk = std::size_t(1) << 16, kBlock = 4096;
  std::vector<PlannedRay> chunk;
  std::vector<EmbreeHit> hits;
  std::vector<std::uint8_t> witness_rays(mesh.object_ids.size(), 0);  // per object index, found so far
  chunk.reserve(kChunk + options.max_samples_per_building);
  while (chunk.clear(), plan.next(chunk, kChunk)) {
    hits.assign(chunk.size(), EmbreeHit{});
    std::atomic<std::size_t> next_block{0};
    auto worker = [&] {
      for (std::size_t begin; (begin = next_block.fetch_add(kBlock)) < chunk.size();) {
        const std::size_t end = std::min(chunk.size(), begin + kBlock);
        for (std::size_t k = begin; k < end; ++k) hits[k] = im.embree.cast(embree_ray_of(chunk[k]));
      }
    };
    const int threads = int(std::min<std::size_t>(std::size_t(options.threads), 1 + chunk.size() / kBlock));
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();

    for (std::size_t k = 0; k < chunk.size(); ++k) {
      if (!hits[k].hit()) continue;
      const std::uint32_t owner = mesh.owner_index[hits[k].triangle];
      // The first and its further ones found (and no triangle asked for).
      if (witness_rays[owner] > kFurtherWitnesses && !triangles) continue;
      const PlannedRay& r = chunk[k];
      const double t = im.embree.exact_t(r.origin, r.direction, hits[k]);
      const Vec3 hit_point = r.origin + r.direction * t;
      if (!volume.contains(hit_point)) continue;
      const WitnessRay w{r.origin,         r.direction, r.t_near, r.t_far, t, hit_point, r.target, hits[k].triangle,
                         r.aimed_at == kNoObjectIndex ? ObjectId(0) : mesh.object_ids[r.aimed_at], r.source};
      if (triangles) triangles->emplace(hits[k].triangle, w);
      if (witness_rays[owner] > kFurtherWitnesses) continue;
      const ObjectId id = mesh.object_ids[owner];
      if (witness_rays[owner]++ == 0)
        result.witnesses.emplace(id, w);
      else
        result.further_witnesses[id].push_back(w);
    }
    result.rays_cast += chunk.size();
    if (log)
      for (const PlannedRay& r : chunk) log->rays.push_back(embree_ray_of(r));
  }
  result.candidates = plan.candidates();
  result.capped_objects = plan.capped_objects();
  result.grazing_rays = plan.grazing_rays();
  for (const auto& [id, ray] : result.witnesses) result.witnessed.push_back(id);
  result.elapsed_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

RayOracle::Replay RayOracle::replay(const WitnessRay& ray, const Camera& camera) const {
  const EmbreeScene& embree = impl_->embree;
  const EmbreeHit hit = embree.cast(to_float(ray.origin - embree.mesh().origin, ray.direction, ray.t_near, ray.t_far));
  Replay out;
  if (!hit.hit()) return out;
  out.hit = embree.mesh().owner_id[hit.triangle];
  out.t_hit = embree.exact_t(ray.origin, ray.direction, hit);
  out.in_view_volume = ViewTransform(camera).contains(ray.origin + ray.direction * out.t_hit);
  return out;
}

bool RayOracle::line_of_sight(Vec3 a, Vec3 b) const {
  const EmbreeScene& embree = impl_->embree;
  const Vec3 o = a - embree.mesh().origin, d = b - a;
  RTCRay ray{};
  ray.org_x = static_cast<float>(o.x), ray.org_y = static_cast<float>(o.y), ray.org_z = static_cast<float>(o.z);
  ray.dir_x = static_cast<float>(d.x), ray.dir_y = static_cast<float>(d.y), ray.dir_z = static_cast<float>(d.z);
  ray.tnear = 0.0f;
  ray.tfar = 1.0f;  // the direction spans the segment
  ray.mask = 0xFFFFFFFFu;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(embree.handle(), &context, &ray);
  return ray.tfar >= 0.0f;  // Embree sets tfar to -inf on a hit
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> RayOracle::mutually_visible(const std::vector<Vec3>& eyes,
                                                                                 int threads) const {
  const auto n = static_cast<std::uint32_t>(eyes.size());
  threads = std::max(1, std::min<int>(threads, static_cast<int>(n)));
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found(static_cast<std::size_t>(threads));
  // Row i has n - 1 - i pairs: rows are dealt round-robin so the threads' shares are even.
  auto worker = [&](int t) {
    for (std::uint32_t i = static_cast<std::uint32_t>(t); i < n; i += static_cast<std::uint32_t>(threads))
      for (std::uint32_t j = i + 1; j < n; ++j)
        if (line_of_sight(eyes[i], eyes[j])) found[static_cast<std::size_t>(t)].emplace_back(i, j);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (std::thread& th : pool) th.join();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
  std::sort(out.begin(), out.end());
  return out;
}

double RayOracle::bare_embree_rays_per_second(const RayLog& log, int threads, double min_seconds) const {
  if (log.rays.empty()) return 0.0;
  threads = std::max(1, threads);
  const RTCScene scene = impl_->embree.handle();
  std::atomic<std::uint64_t> sink{0};
  std::uint64_t passes = 0;
  const auto start = Clock::now();
  double seconds = 0.0;
  do {
    auto worker = [&](std::size_t begin, std::size_t end) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      std::uint64_t hits = 0;
      for (std::size_t k = begin; k < end; ++k) {
        RTCRayHit rh = embree_ray(log.rays[k]);
        rtcIntersect1(scene, &context, &rh);
        hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
      sink += hits;  // keeps the loop observable
    };
    std::vector<std::thread> pool;
    const std::size_t n = log.rays.size();
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker, n * t / threads, n * (t + 1) / threads);
    worker(0, n / threads);
    for (auto& th : pool) th.join();
    ++passes;
    seconds = std::chrono::duration<double>(Clock::now() - start).count();
  } while (seconds < min_seconds);
  return double(passes * log.rays.size()) / seconds;
}

namespace {
const char* source_name(RaySource s) {
  switch (s) {
    case RaySource::surface_sample: return "surface-sample";
    case RaySource::stratified: return "stratified";
    case RaySource::pixel: return "pixel";
    case RaySource::grazing: return "grazing";
  }
  return "?";
}
}  // namespace

std::string describe(const WitnessRay& r) {
  char line[512];
  std::snprintf(line, sizeof line,
                "%s ray org=(%.17g, %.17g, %.17g) dir=(%.17g, %.17g, %.17g) t=[%.9g, %.9g] hit t=%.9g at "
                "(%.9g, %.9g, %.9g) triangle %u aimed at object %u target (%.9g, %.9g, %.9g)",
                source_name(r.source), r.origin.x, r.origin.y, r.origin.z,
                r.direction.x, r.direction.y, r.direction.z, r.t_near, r.t_far, r.t_hit, r.hit_point.x, r.hit_point.y,
                r.hit_point.z, r.triangle, r.aimed_at, r.target.x, r.target.y, r.target.z);
  return line;
}

void to_json(nlohmann::json& j, const WitnessRay& r) {
  auto v = [](Vec3 p) { return nlohmann::json::array({p.x, p.y, p.z}); };
  j = {{"source", r.source == RaySource::stratified ? "stratified"
                  : r.source == RaySource::pixel    ? "pixel"
                  : r.source == RaySource::grazing  ? "grazing"
                                                    : "surface_sample"},
       {"origin", v(r.origin)},
       {"direction", v(r.direction)},
       {"t_near", r.t_near},
       {"t_far", r.t_far},
       {"t_hit", r.t_hit},
       {"hit_point", v(r.hit_point)},
       {"target", v(r.target)},
       {"triangle", r.triangle}};
  if (r.source == RaySource::surface_sample || r.source == RaySource::grazing) j["aimed_at"] = r.aimed_at;
}

}  // namespace cullcheck::oracle
