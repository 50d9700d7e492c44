#include "oracle/embree_scene.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <stdexcept>
#include <string>

namespace cullcheck::oracle {
namespace {

void check_embree(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree error ") + std::to_string(int(e)) + " in " + what);
}

// rtcIntersect1's context, extended with what the filter needs (Embree hands the filter the
// context pointer it was given, so the extension travels with it).
struct FilteredContext {
  RTCIntersectContext context;  // first member: the pointer Embree passes back is this struct's
  const std::uint32_t* owner_index;
  const std::uint8_t* allowed;
};

void keep_allowed_objects(const RTCFilterFunctionNArguments* args) {
  const auto* c = reinterpret_cast<const FilteredContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    if (!c->allowed[c->owner_index[prim]]) args->valid[i] = 0;  // rejected: traversal goes on
  }
}

}  // namespace

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

EmbreeScene::EmbreeScene(const Scene& s) : mesh_(triangulate(s)) {
  device_ = rtcNewDevice("threads=1,set_affinity=0,verbose=0");
  if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  if (!rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
    throw std::runtime_error("Embree was built without filter functions (EMBREE_FILTER_FUNCTION); the pixel oracle needs them");
  scene_ = rtcNewScene(device_);
  // The context filter is what cast_among uses; it changes neither the BVH nor unfiltered hits.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  if (!mesh_.triangles.empty()) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh_.vertices.size()));
    auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), mesh_.triangles.size()));
    check_embree(device_, "buffer allocation");
    for (std::size_t i = 0; i < mesh_.vertices.size(); ++i) {
      const Vec3 p = mesh_.vertices[i] - mesh_.origin;
      v[3 * i] = float(p.x), v[3 * i + 1] = float(p.y), v[3 * i + 2] = float(p.z);
    }
    for (std::size_t i = 0; i < mesh_.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) t[3 * i + k] = mesh_.triangles[i][k];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene_);
  check_embree(device_, "scene build");
  for (auto [property, width] : {std::pair{RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED, 16}, {RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED, 8},
                                 {RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED, 4}})
    if (rtcGetDeviceProperty(device_, property)) {
      packet_width_ = width;
      break;
    }
}

namespace {

// One packet of `Width` lanes (RTCRayHit4, 8 or 16): lanes past n are invalid.
template <int Width, typename Packet, typename Intersect>
void cast_lanes(RTCScene scene, FilteredContext& context, const RayLog::Ray* rays, std::size_t n, EmbreeHit* hits,
                Intersect intersect) {
  alignas(64) Packet p;
  alignas(64) int valid[Width];
  for (int i = 0; i < Width; ++i) {
    const auto k = std::size_t(i);
    valid[i] = k < n ? -1 : 0;
    const RayLog::Ray& r = rays[k < n ? k : 0];
    p.ray.org_x[i] = r.org[0], p.ray.org_y[i] = r.org[1], p.ray.org_z[i] = r.org[2];
    p.ray.dir_x[i] = r.dir[0], p.ray.dir_y[i] = r.dir[1], p.ray.dir_z[i] = r.dir[2];
    p.ray.tnear[i] = r.t_near, p.ray.tfar[i] = r.t_far;
    p.ray.mask[i] = 0xFFFFFFFFu, p.ray.time[i] = 0.0f, p.ray.flags[i] = 0, p.ray.id[i] = unsigned(i);
    p.hit.geomID[i] = p.hit.primID[i] = p.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  intersect(valid, scene, &context.context, &p);
  for (std::size_t k = 0; k < n; ++k)
    hits[k] = p.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? EmbreeHit{} : EmbreeHit{p.ray.tfar[k], p.hit.primID[k]};
}

}  // namespace

void EmbreeScene::cast_packet(const RayLog::Ray* rays, std::size_t n, EmbreeHit* hits,
                              const std::vector<std::uint8_t>* allowed_objects) const {
  if (n > kPacket) throw std::logic_error("EmbreeScene::cast_packet: more than kPacket rays");
  FilteredContext c;
  rtcInitIntersectContext(&c.context);
  c.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  if (allowed_objects) {
    c.context.filter = keep_allowed_objects;
    c.owner_index = mesh_.owner_index.data();
    c.allowed = allowed_objects->data();
  }
  switch (packet_width_) {
    case 16: return cast_lanes<16, RTCRayHit16>(scene_, c, rays, n, hits, rtcIntersect16);
    case 8:
      for (std::size_t k = 0; k < n; k += 8) cast_lanes<8, RTCRayHit8>(scene_, c, rays + k, std::min<std::size_t>(8, n - k), hits + k, rtcIntersect8);
      return;
    case 4:
      for (std::size_t k = 0; k < n; k += 4) cast_lanes<4, RTCRayHit4>(scene_, c, rays + k, std::min<std::size_t>(4, n - k), hits + k, rtcIntersect4);
      return;
    default:
      for (std::size_t k = 0; k < n; ++k) hits[k] = allowed_objects ? cast_among(rays[k], *allowed_objects) : cast(rays[k]);
  }
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

EmbreeHit EmbreeScene::cast(const RayLog::Ray& r) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = embree_ray(r);
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  return {rh.ray.tfar, rh.hit.primID};
}

EmbreeHit EmbreeScene::cast_among(const RayLog::Ray& r, const std::vector<std::uint8_t>& allowed_objects) const {
  FilteredContext c;
  rtcInitIntersectContext(&c.context);
  c.context.filter = keep_allowed_objects;
  c.owner_index = mesh_.owner_index.data();
  c.allowed = allowed_objects.data();
  RTCRayHit rh = embree_ray(r);
  rtcIntersect1(scene_, &c.context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  return {rh.ray.tfar, rh.hit.primID};
}

double EmbreeScene::exact_t(Vec3 origin, Vec3 d, const EmbreeHit& hit) const {
  const auto& tri = mesh_.triangles[hit.triangle];
  const Vec3 a = mesh_.vertices[tri[0]], b = mesh_.vertices[tri[1]], c = mesh_.vertices[tri[2]];
  const Vec3 n = cross(b - a, c - a);
  const double denom = dot(n, d);
  if (std::abs(denom) <= 1e-9 * length(n)) return hit.t;
  return dot(n, a - origin) / denom;
}

}  // namespace cullcheck::oracle
