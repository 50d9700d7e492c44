#include "oracle/witness_recheck.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "oracle/view_transform.hpp"

namespace cullcheck::oracle {
namespace {

double component(Vec3 v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

// Whether the ray meets the box over [t0, t1] (slab test). The box is widened by a relative
// 1e-9 (plus 1e-9 m) so that rounding in the slab arithmetic can only keep a box, never drop one
// holding a triangle the watertight test would hit.
bool meets(const Box3& b, Vec3 o, Vec3 d, double t0, double t1) {
  for (int k = 0; k < 3; ++k) {
    const double lo = component(b.lo, k), hi = component(b.hi, k);
    const double pad = 1e-9 * (std::abs(lo) + std::abs(hi) + (hi - lo)) + 1e-9;
    const double ok = component(o, k), dk = component(d, k);
    if (dk == 0.0) {
      if (ok < lo - pad || ok > hi + pad) return false;
      continue;
    }
    double a = (lo - pad - ok) / dk, c = (hi + pad - ok) / dk;
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a), t1 = std::min(t1, c);
    if (t0 > t1 * (1 + 1e-12) + 1e-12) return false;
  }
  return true;
}

// Watertight ray/triangle intersection (Woop, Benthin, Wald, JCGT 2013) in double precision:
// the triangle is sheared into the ray's frame and the three edge functions are evaluated there,
// so an edge shared by two triangles gives both the same value with opposite signs and no ray
// passes between them. Edges are inclusive. Returns t, or NaN for a miss.
double watertight_t(Vec3 o, Vec3 d, Vec3 a, Vec3 b, Vec3 c) {
  int kz = 0;
  if (std::abs(d.y) > std::abs(component(d, kz))) kz = 1;
  if (std::abs(d.z) > std::abs(component(d, kz))) kz = 2;
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (component(d, kz) < 0.0) std::swap(kx, ky);  // keep the winding
  const double sz = 1.0 / component(d, kz);
  const double sx = component(d, kx) * sz, sy = component(d, ky) * sz;
  const Vec3 A = a - o, B = b - o, C = c - o;
  const double ax = component(A, kx) - sx * component(A, kz), ay = component(A, ky) - sy * component(A, kz);
  const double bx = component(B, kx) - sx * component(B, kz), by = component(B, ky) - sy * component(B, kz);
  const double cx = component(C, kx) - sx * component(C, kz), cy = component(C, ky) - sy * component(C, kz);
  long double u = (long double)cx * by - (long double)cy * bx;
  long double v = (long double)ax * cy - (long double)ay * cx;
  long double w = (long double)bx * ay - (long double)by * ax;
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return std::numeric_limits<double>::quiet_NaN();
  const long double det = u + v + w;
  if (det == 0) return std::numeric_limits<double>::quiet_NaN();  // seen edge-on
  const long double az = sz * component(A, kz), bz = sz * component(B, kz), cz = sz * component(C, kz);
  return double((u * az + v * bz + w * cz) / det);
}

}  // namespace

const char* name(RecheckVerdict v) {
  switch (v) {
    case RecheckVerdict::stands: return "stands";
    case RecheckVerdict::blocked: return "blocked";
    case RecheckVerdict::reaches_nothing: return "reaches_nothing";
    case RecheckVerdict::outside_view: return "outside_view";
  }
  return "?";
}

std::string WitnessRecheck::describe() const {
  char line[160];
  if (verdict == RecheckVerdict::reaches_nothing) return "reaches nothing in double precision";
  std::snprintf(line, sizeof line, "%s: first hit in double precision is object %u at t = %.17g", name(verdict),
                first_hit ? *first_hit : 0u, t_hit);
  return line;
}

DoublePrecisionScene::DoublePrecisionScene(const TriangleMesh& mesh) : mesh_(mesh) {
  const std::size_t objects = mesh.object_ids.size();
  boxes_.assign(objects, Box3{});
  first_.assign(objects, 0), end_.assign(objects, 0);
  std::vector<std::uint8_t> seen(objects, 0);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::uint32_t k = mesh.owner_index[t];
    if (!seen[k]) seen[k] = 1, first_[k] = t, end_[k] = t;
    if (end_[k] != t) throw std::logic_error("DoublePrecisionScene: an object's triangles are not contiguous in the mesh");
    end_[k] = t + 1;
    for (std::uint32_t v : mesh.triangles[t]) boxes_[k].extend(mesh.vertices[v]);
  }
}

std::optional<DoublePrecisionScene::Hit> DoublePrecisionScene::first_hit(Vec3 o, Vec3 d, double t_near, double t_far,
                                                                         std::uint32_t prefer) const {
  std::optional<Hit> best;
  for (std::uint32_t k = 0; k < boxes_.size(); ++k) {
    if (first_[k] == end_[k] || !meets(boxes_[k], o, d, t_near, best ? best->t : t_far)) continue;
    for (std::uint32_t t = first_[k]; t < end_[k]; ++t) {
      const auto& tri = mesh_.triangles[t];
      const double hit = watertight_t(o, d, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]], mesh_.vertices[tri[2]]);
      if (!(hit >= t_near && hit <= t_far)) continue;  // NaN (a miss) fails both
      if (!best || hit < best->t || (hit == best->t && k == prefer && best->object_index != prefer)) best = Hit{hit, k, t};
    }
  }
  return best;
}

WitnessRecheck DoublePrecisionScene::recheck(const WitnessRay& ray, ObjectId object, const Camera& camera) const {
  std::uint32_t index = UINT32_MAX;
  for (std::uint32_t k = 0; k < mesh_.object_ids.size(); ++k)
    if (mesh_.object_ids[k] == object) index = k;
  WitnessRecheck out;
  const std::optional<Hit> hit = first_hit(ray.origin, ray.direction, ray.t_near, ray.t_far, index);
  if (!hit) {
    out.verdict = RecheckVerdict::reaches_nothing;
    return out;
  }
  out.first_hit = mesh_.object_ids[hit->object_index];
  out.t_hit = hit->t;
  if (hit->object_index != index)
    out.verdict = RecheckVerdict::blocked;
  else if (!ViewTransform(camera).contains(ray.origin + ray.direction * hit->t))
    out.verdict = RecheckVerdict::outside_view;
  return out;
}

}  // namespace cullcheck::oracle
