#include "oracle/embree_scene.hpp"

#include <cmath>
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

RayLog::Ray to_float(Vec3 o, Vec3 d, double t_near, double t_far) {
  return {{float(o.x), float(o.y), float(o.z)},
          {float(d.x), float(d.y), float(d.z)},
          float(t_near),
          std::nextafter(float(t_far), std::numeric_limits<float>::infinity())};
}

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
