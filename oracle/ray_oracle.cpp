#include "oracle/ray_oracle.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "oracle/embree_scene.hpp"
#include "oracle/ray_plan.hpp"
#include "oracle/sample_cache.hpp"
#include "oracle/view_transform.hpp"

namespace cullcheck::oracle {
namespace {

using Clock = std::chrono::steady_clock;

// One unit of the plan (an object, or a run of stratified cells), cast and sifted on one thread:
// its witnessing rays in ray order, at most 1 + kFurtherWitnesses per object (the merge keeps no
// more, so later ones cannot matter), and with `triangles` the first per triangle.
struct UnitResult {
  std::vector<std::pair<std::uint32_t, WitnessRay>> witnesses;  // (object index, ray)
  std::vector<std::pair<std::uint32_t, WitnessRay>> triangles;  // (triangle, ray)
  std::vector<RayLog::Ray> log;
  std::uint64_t rays = 0, skipped = 0;

  void clear() { witnesses.clear(), triangles.clear(), log.clear(), rays = skipped = 0; }
};

// A thread's scratch: the rays of the unit in hand, and per object (and triangle) how many
// witnesses this unit has found so far, reset through the lists of entries touched.
struct Sifter {
  UnitRays unit;
  SurfaceSamples samples;
  std::vector<std::uint8_t> found;
  std::vector<std::uint8_t> triangle_found;
  std::vector<std::uint32_t> touched, touched_triangles;
  PlanTally tally;

  void reset() {
    for (std::uint32_t o : touched) found[o] = 0;
    for (std::uint32_t t : touched_triangles) triangle_found[t] = 0;
    touched.clear(), touched_triangles.clear();
  }
};

// Surface-sample rays of an object are cast a packet at a time between looks at whether the
// object is witnessed enough to stop (SamplingOptions::stop_when_witnessed).
constexpr std::size_t kEarlyOutGroup = EmbreeScene::kPacket;
// Stratified cells per unit: a few thousand rays, so the units even out across threads.
constexpr std::size_t kCellsPerUnit = 2048;
// Units merged per wave: the results of one wave are held at once.
constexpr std::size_t kWave = 1024;

// A query's scratch: a sifter per thread and the wave's result slots. Kept by the oracle between
// queries (a walk asks hundreds), so their memory is allocated once rather than every frame.
struct QueryScratch {
  std::vector<Sifter> sifters;
  std::vector<UnitResult> slots;
};

}  // namespace

struct RayOracle::Impl {
  const Scene& scene;
  EmbreeScene embree;
  // Surface samples kept across queries (they do not depend on the camera); thread-safe.
  mutable SampleCache samples;
  // Scratch of finished queries, taken by the next ones (concurrent queries each take their own).
  mutable std::mutex scratch_mutex;
  mutable std::vector<std::unique_ptr<QueryScratch>> scratch;

  explicit Impl(const Scene& s) : scene(s), embree(s), samples(s, embree.mesh()) {}

  std::unique_ptr<QueryScratch> take_scratch() const {
    const std::lock_guard<std::mutex> lock(scratch_mutex);
    if (scratch.empty()) return std::make_unique<QueryScratch>();
    std::unique_ptr<QueryScratch> s = std::move(scratch.back());
    scratch.pop_back();
    return s;
  }
  void give_back(std::unique_ptr<QueryScratch> s) const {
    const std::lock_guard<std::mutex> lock(scratch_mutex);
    scratch.push_back(std::move(s));
  }
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
  const RayPlan plan(im.scene, mesh, camera, options, &im.samples);
  const ViewTransform& volume = plan.cone().transform();
  const std::size_t objects = plan.objects(), cells = plan.cells();
  const std::size_t units = objects + (cells + kCellsPerUnit - 1) / kCellsPerUnit;

  // Cast unit u's rays [begin, end) and keep what the merge can use. A ray is a witness of the
  // object its first hit lies on when that hit (recomputed in double precision) is in the view
  // volume.
  auto sift = [&](Sifter& s, UnitResult& out, std::size_t begin, std::size_t end) {
    EmbreeHit hits[EmbreeScene::kPacket];
    for (std::size_t first = begin; first < end; first += EmbreeScene::kPacket) {
      const std::size_t n = std::min(EmbreeScene::kPacket, end - first);
      const RayLog::Ray* packet = s.unit.cast.data() + first;
      if (log) out.log.insert(out.log.end(), packet, packet + n);
      im.embree.cast_packet(packet, n, hits);
      for (std::size_t i = 0; i < n; ++i) {
        const EmbreeHit& hit = hits[i];
        if (!hit.hit()) continue;
        const std::uint32_t owner = mesh.owner_index[hit.triangle];
        const bool for_object = s.found[owner] <= kFurtherWitnesses;
        const bool for_triangle = triangles && !s.triangle_found[hit.triangle];
        if (!for_object && !for_triangle) continue;
        const PlannedRay r = plan.planned(s.unit, first + i);  // the double-precision ray cast[first + i] rounds
        const double t = im.embree.exact_t(r.origin, r.direction, hit);
        const Vec3 hit_point = r.origin + r.direction * t;
        if (!volume.contains(hit_point)) continue;
        const WitnessRay w{r.origin,         r.direction, r.t_near, r.t_far, t, hit_point, r.target, hit.triangle,
                           r.aimed_at == kNoObjectIndex ? ObjectId(0) : mesh.object_ids[r.aimed_at], r.source};
        if (for_triangle) {
          if (s.triangle_found[hit.triangle]++ == 0) s.touched_triangles.push_back(hit.triangle);
          out.triangles.emplace_back(hit.triangle, w);
        }
        if (for_object) {
          if (s.found[owner]++ == 0) s.touched.push_back(owner);
          out.witnesses.emplace_back(owner, w);
        }
      }
    }
    out.rays += end - begin;
  };
  auto run_unit = [&](Sifter& s, std::size_t u, UnitResult& out) {
    out.clear();
    if (u < objects) {
      const auto index = std::uint32_t(u);
      const std::size_t surface = plan.object_rays(index, s.unit, s.tally, s.samples);
      // Its surface samples until the object has all the witnesses the merge keeps, then its
      // grazing rays, which look past its silhouette at what lies behind.
      std::size_t k = 0;
      while (k < surface) {
        if (options.stop_when_witnessed && !triangles && s.found[index] > kFurtherWitnesses) break;
        const std::size_t group_end = std::min(surface, k + kEarlyOutGroup);
        sift(s, out, k, group_end);
        k = group_end;
      }
      out.skipped = surface - k;
      sift(s, out, surface, s.unit.size());
    } else {
      const std::size_t first = (u - objects) * kCellsPerUnit;
      plan.cell_rays(first, first + kCellsPerUnit, s.unit);
      sift(s, out, 0, s.unit.size());
    }
    s.reset();
  };

  // Wave by wave, in plan order: the threads take units of the wave as they come free and write
  // each unit's result in its own slot; then the slots are merged in unit order. An object is
  // witnessed by the first ray in plan order whose first hit lies on it inside the view volume,
  // whatever the thread count.
  const int threads = int(std::min<std::size_t>(std::size_t(options.threads), std::max<std::size_t>(1, units)));
  // Each sifter's counts are back at zero after every unit (Sifter::reset), so kept ones can be reused.
  std::unique_ptr<QueryScratch> scratch = im.take_scratch();
  std::vector<Sifter>& sifters = scratch->sifters;
  if (sifters.size() < std::size_t(threads)) sifters.resize(std::size_t(threads));
  for (Sifter& s : sifters) {
    s.tally = PlanTally{};
    if (s.found.size() != mesh.object_ids.size()) s.found.assign(mesh.object_ids.size(), 0);
    if (triangles && s.triangle_found.size() != mesh.triangles.size()) s.triangle_found.assign(mesh.triangles.size(), 0);
  }
  std::vector<UnitResult>& slots = scratch->slots;
  if (slots.size() < std::min(units, kWave)) slots.resize(std::min(units, kWave));
  std::vector<std::uint8_t> witness_rays(mesh.object_ids.size(), 0);  // per object index, found so far
  for (std::size_t wave = 0; wave < units; wave += kWave) {
    const std::size_t wave_end = std::min(units, wave + kWave);
    std::atomic<std::size_t> next_unit{wave};
    std::exception_ptr failure;
    std::atomic<bool> failed{false};
    auto worker = [&](Sifter& s) {
      try {
        for (std::size_t u; !failed && (u = next_unit.fetch_add(1)) < wave_end;) run_unit(s, u, slots[u - wave]);
      } catch (...) {
        if (!failed.exchange(true)) failure = std::current_exception();
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads && wave + std::size_t(t) < wave_end; ++t) pool.emplace_back(worker, std::ref(sifters[std::size_t(t)]));
    worker(sifters[0]);
    for (auto& th : pool) th.join();
    if (failure) std::rethrow_exception(failure);

    for (std::size_t u = wave; u < wave_end; ++u) {
      UnitResult& unit = slots[u - wave];
      for (auto& [owner, w] : unit.witnesses) {
        if (witness_rays[owner] > kFurtherWitnesses) continue;
        const ObjectId id = mesh.object_ids[owner];
        if (witness_rays[owner]++ == 0)
          result.witnesses.emplace(id, w);
        else
          result.further_witnesses[id].push_back(w);
      }
      if (triangles)
        for (auto& [triangle, w] : unit.triangles) triangles->emplace(triangle, w);  // a triangle already there keeps its ray
      if (log) log->rays.insert(log->rays.end(), unit.log.begin(), unit.log.end());
      result.rays_cast += unit.rays;
      result.rays_skipped += unit.skipped;
    }
  }
  for (const Sifter& s : sifters) {
    result.candidates += s.tally.candidates;
    result.capped_objects += s.tally.capped;
    result.grazing_rays += s.tally.grazing;
  }
  im.give_back(std::move(scratch));
  for (const auto& [id, ray] : result.witnesses) result.witnessed.push_back(id);
  result.elapsed_seconds = seconds_since(start);
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

double RayOracle::bare_embree_rays_per_second(const RayLog& log, int threads, double min_seconds, bool packets) const {
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
      if (packets) {
        EmbreeHit found[EmbreeScene::kPacket];
        for (std::size_t k = begin; k < end; k += EmbreeScene::kPacket) {
          const std::size_t n = std::min(EmbreeScene::kPacket, end - k);
          impl_->embree.cast_packet(&log.rays[k], n, found);
          for (std::size_t i = 0; i < n; ++i) hits += found[i].hit();
        }
      } else {
        for (std::size_t k = begin; k < end; ++k) {
          RTCRayHit rh = embree_ray(log.rays[k]);
          rtcIntersect1(scene, &context, &rh);
          hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
      }
      sink += hits;  // keeps the loop observable
    };
    std::vector<std::thread> pool;
    const std::size_t n = log.rays.size();
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker, n * t / threads, n * (t + 1) / threads);
    worker(0, n / threads);
    for (auto& th : pool) th.join();
    ++passes;
    seconds = seconds_since(start);
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
