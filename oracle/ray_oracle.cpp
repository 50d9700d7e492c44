#include "oracle/ray_oracle.hpp"

#include <embree3/rtcore.h>

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
#include "oracle/ray_plan.hpp"

namespace cullcheck::oracle {
namespace {

using Clock = std::chrono::steady_clock;

struct Hit {
  float t = 0.0f;
  std::uint32_t triangle = RTC_INVALID_GEOMETRY_ID;
};

RTCRayHit embree_ray(const RayLog::Ray& r) {
  RTCRayHit rh{};
  rh.ray.org_x = r.org[0], rh.ray.org_y = r.org[1], rh.ray.org_z = r.org[2];
  rh.ray.dir_x = r.dir[0], rh.ray.dir_y = r.dir[1], rh.ray.dir_z = r.dir[2];
  rh.ray.tnear = r.t_near;
  rh.ray.tfar = r.t_far;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.time = 0.0f;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

RayLog::Ray to_float(Vec3 eye_local, Vec3 direction, double t_near, double t_far) {
  return {{float(eye_local.x), float(eye_local.y), float(eye_local.z)},
          {float(direction.x), float(direction.y), float(direction.z)},
          float(t_near),
          // Rounding t_far down could stop a ray just short of its sample's face.
          std::nextafter(float(t_far), std::numeric_limits<float>::infinity())};
}

void check_embree(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree error ") + std::to_string(int(e)) + " in " + what);
}

}  // namespace

struct RayOracle::Impl {
  const Scene& scene;
  TriangleMesh mesh;
  RTCDevice device = nullptr;
  RTCScene rtc_scene = nullptr;

  explicit Impl(const Scene& s) : scene(s), mesh(triangulate(s)) {
    // One build thread: the BVH, and so the choice between exactly equal hits, is then the
    // same on every run. Rays are cast from our own threads (rtcIntersect1 is thread-safe).
    device = rtcNewDevice("threads=1,set_affinity=0,verbose=0");
    if (!device) throw std::runtime_error("Embree: rtcNewDevice failed (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtc_scene = rtcNewScene(device);
    rtcSetSceneFlags(rtc_scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(rtc_scene, RTC_BUILD_QUALITY_HIGH);
    if (!mesh.triangles.empty()) {
      RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), mesh.vertices.size()));
      auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), mesh.triangles.size()));
      check_embree(device, "buffer allocation");
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Vec3 p = mesh.vertices[i] - mesh.origin;
        v[3 * i] = float(p.x), v[3 * i + 1] = float(p.y), v[3 * i + 2] = float(p.z);
      }
      for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) t[3 * i + k] = mesh.triangles[i][k];
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(rtc_scene, geometry);
      rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(rtc_scene);
    check_embree(device, "scene build");
  }
  ~Impl() {
    if (rtc_scene) rtcReleaseScene(rtc_scene);
    if (device) rtcReleaseDevice(device);
  }

  Hit cast(const RayLog::Ray& r) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = embree_ray(r);
    rtcIntersect1(rtc_scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
    return {rh.ray.tfar, rh.hit.primID};
  }

  // The hit recomputed in double precision on the hit triangle's plane, so the view-volume test
  // is not blurred by Embree's float t (falls back to it for rays grazing the plane).
  double exact_t(Vec3 eye, Vec3 d, const Hit& hit) const {
    const auto& tri = mesh.triangles[hit.triangle];
    const Vec3 a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
    const Vec3 n = cross(b - a, c - a);
    const double denom = dot(n, d);
    if (std::abs(denom) <= 1e-9 * length(n)) return hit.t;
    return dot(n, a - eye) / denom;
  }
};

RayOracle::RayOracle(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
RayOracle::~RayOracle() = default;
const TriangleMesh& RayOracle::mesh() const { return impl_->mesh; }
const Scene& RayOracle::scene() const { return impl_->scene; }

OracleResult RayOracle::witness(const Camera& camera, const SamplingOptions& options, RayLog* log) const {
  const auto start = Clock::now();
  validate(camera);
  validate(options);
  const Impl& im = *impl_;
  const Vec3 eye = camera.position;
  const Vec3 eye_local = eye - im.mesh.origin;
  OracleResult result;
  result.density = options;
  RayPlan plan(im.scene, camera, options);
  const ViewVolume& volume = plan.cone().volume();

  // Chunk by chunk, in plan order: cast the chunk (each thread takes blocks and writes hits at
  // the rays' own indices), then merge it in ray order. A building is witnessed by the first
  // ray whose first hit lies on it and inside the view volume, whatever the thread count.
  constexpr std::size_t kChunk = std::size_t(1) << 16, kBlock = 4096;
  std::vector<PlannedRay> chunk;
  std::vector<Hit> hits;
  chunk.reserve(kChunk + options.max_samples_per_building);
  while (chunk.clear(), plan.next(chunk, kChunk)) {
    hits.assign(chunk.size(), Hit{});
    std::atomic<std::size_t> next_block{0};
    auto worker = [&] {
      for (std::size_t begin; (begin = next_block.fetch_add(kBlock)) < chunk.size();) {
        const std::size_t end = std::min(chunk.size(), begin + kBlock);
        for (std::size_t k = begin; k < end; ++k)
          hits[k] = im.cast(to_float(eye_local, chunk[k].direction, chunk[k].t_near, chunk[k].t_far));
      }
    };
    const int threads = int(std::min<std::size_t>(std::size_t(options.threads), 1 + chunk.size() / kBlock));
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();

    for (std::size_t k = 0; k < chunk.size(); ++k) {
      if (hits[k].triangle == RTC_INVALID_GEOMETRY_ID) continue;
      const ObjectId id = im.mesh.owner_id[hits[k].triangle];
      if (result.witnesses.count(id)) continue;
      const PlannedRay& r = chunk[k];
      const double t = im.exact_t(eye, r.direction, hits[k]);
      const Vec3 hit_point = eye + r.direction * t;
      if (!volume.contains(hit_point)) continue;
      result.witnesses.emplace(id, WitnessRay{eye, r.direction, r.t_near, r.t_far, t, hit_point, r.target,
                                              hits[k].triangle,
                                              r.aimed_at == kNoBuilding ? ObjectId(0) : im.scene.buildings[r.aimed_at].id,
                                              r.source});
    }
    result.rays_cast += chunk.size();
    if (log)
      for (const PlannedRay& r : chunk) log->rays.push_back(to_float(eye_local, r.direction, r.t_near, r.t_far));
  }
  result.candidates = plan.candidates();
  result.capped_buildings = plan.capped_buildings();
  for (const auto& [id, ray] : result.witnesses) result.witnessed.push_back(id);
  result.elapsed_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

RayOracle::Replay RayOracle::replay(const WitnessRay& ray, const Camera& camera) const {
  const Impl& im = *impl_;
  const Hit hit = im.cast(to_float(ray.origin - im.mesh.origin, ray.direction, ray.t_near, ray.t_far));
  Replay out;
  if (hit.triangle == RTC_INVALID_GEOMETRY_ID) return out;
  out.hit = im.mesh.owner_id[hit.triangle];
  out.t_hit = im.exact_t(ray.origin, ray.direction, hit);
  out.in_view_volume = ViewVolume(camera).contains(ray.origin + ray.direction * out.t_hit);
  return out;
}

bool RayOracle::line_of_sight(Vec3 a, Vec3 b) const {
  const Impl& im = *impl_;
  const Vec3 o = a - im.mesh.origin, d = b - a;
  RTCRay ray{};
  ray.org_x = static_cast<float>(o.x), ray.org_y = static_cast<float>(o.y), ray.org_z = static_cast<float>(o.z);
  ray.dir_x = static_cast<float>(d.x), ray.dir_y = static_cast<float>(d.y), ray.dir_z = static_cast<float>(d.z);
  ray.tnear = 0.0f;
  ray.tfar = 1.0f;  // the direction spans the segment
  ray.mask = 0xFFFFFFFFu;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(im.rtc_scene, &context, &ray);
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
  const RTCScene scene = impl_->rtc_scene;
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

std::string describe(const WitnessRay& r) {
  char line[512];
  std::snprintf(line, sizeof line,
                "%s ray org=(%.17g, %.17g, %.17g) dir=(%.17g, %.17g, %.17g) t=[%.9g, %.9g] hit t=%.9g at "
                "(%.9g, %.9g, %.9g) triangle %u aimed at building %u target (%.9g, %.9g, %.9g)",
                r.source == RaySource::stratified ? "stratified" : "surface-sample", r.origin.x, r.origin.y, r.origin.z,
                r.direction.x, r.direction.y, r.direction.z, r.t_near, r.t_far, r.t_hit, r.hit_point.x, r.hit_point.y,
                r.hit_point.z, r.triangle, r.aimed_at, r.target.x, r.target.y, r.target.z);
  return line;
}

void to_json(nlohmann::json& j, const WitnessRay& r) {
  auto v = [](Vec3 p) { return nlohmann::json::array({p.x, p.y, p.z}); };
  j = {{"source", r.source == RaySource::stratified ? "stratified" : "surface_sample"},
       {"origin", v(r.origin)},
       {"direction", v(r.direction)},
       {"t_near", r.t_near},
       {"t_far", r.t_far},
       {"t_hit", r.t_hit},
       {"hit_point", v(r.hit_point)},
       {"target", v(r.target)},
       {"triangle", r.triangle}};
  if (r.source == RaySource::surface_sample) j["aimed_at"] = r.aimed_at;
}

}  // namespace cullcheck::oracle
