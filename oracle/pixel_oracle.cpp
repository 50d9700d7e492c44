#include "oracle/pixel_oracle.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "oracle/embree_scene.hpp"
#include "oracle/view_transform.hpp"

namespace cullcheck::oracle {
namespace {

// The camera's pixel rays (the header's conventions) in the oracle's own view transform.
class PixelRays {
 public:
  explicit PixelRays(const Camera& c) : camera_(c), view_(c), resolution_(resolution_of(c)) {}

  Resolution resolution() const { return resolution_; }
  const ViewTransform& view() const { return view_; }

  WitnessRay ray(int i, int j) const {
    const double u = 2.0 * (i + 0.5) / resolution_.width - 1.0;
    const double v = 1.0 - 2.0 * (j + 0.5) / resolution_.height;
    WitnessRay r;
    r.source = RaySource::pixel;
    r.origin = camera_.position;
    if (camera_.orthographic()) {
      // On the eye plane: the near-plane point of (u, v) moved back by near.
      r.origin = view_.near_point_at(u, v) - view_.forward() * camera_.near;
      r.direction = view_.forward();
      r.t_near = camera_.near, r.t_far = camera_.far;
    } else if (camera_.omnidirectional()) {
      const double azimuth = kTwoPi * (i + 0.5) / resolution_.width;
      const double elevation = kPi / 2 - kPi * (j + 0.5) / resolution_.height;
      r.direction = {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
      r.t_near = 0.0, r.t_far = camera_.far;
    } else {
      r.direction = view_.direction_through(u, v);
      const double along = dot(view_.forward(), r.direction);
      r.t_near = camera_.near / along, r.t_far = camera_.far / along;
    }
    r.target = r.origin + r.direction * r.t_far;
    return r;
  }

 private:
  const Camera& camera_;
  ViewTransform view_;
  Resolution resolution_;
};

// Casts pixels pixel_at(0..n-1) (row-major indices, n at most a packet) as one packet, among the
// objects `allowed` flags when given, and writes the object each shows (or kNoObject) to ids.
template <class PixelAt>
void cast_pixels(const PixelRays& rays, const EmbreeScene& embree, std::size_t n, PixelAt pixel_at,
                 const std::vector<std::uint8_t>* allowed, std::vector<ObjectId>& ids) {
  const TriangleMesh& mesh = embree.mesh();
  const auto width = std::size_t(rays.resolution().width);
  RayLog::Ray packet[EmbreeScene::kPacket]{};  // lanes past n are never read; initialised for the compiler
  EmbreeHit hits[EmbreeScene::kPacket];
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t p = pixel_at(k);
    const WitnessRay r = rays.ray(int(p % width), int(p / width));
    packet[k] = to_float(r.origin - mesh.origin, r.direction, r.t_near, r.t_far);
  }
  embree.cast_packet(packet, n, hits, allowed);
  for (std::size_t k = 0; k < n; ++k) ids[pixel_at(k)] = hits[k].hit() ? mesh.owner_id[hits[k].triangle] : kNoObject;
}

// Runs body(k) for k in [0, count) on `threads` threads, in blocks taken from a shared counter.
// Each k is handled by exactly one thread, so results written at k do not depend on `threads`.
template <class Body>
void parallel_for(std::size_t count, int threads, std::size_t block, Body&& body) {
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t begin; (begin = next.fetch_add(block)) < count;)
      for (std::size_t k = begin, end = std::min(count, begin + block); k < end; ++k) body(k);
  };
  const int n = int(std::clamp<std::size_t>(std::size_t(std::max(threads, 1)), 1, 1 + count / block));
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
}

std::vector<ObjectId> sorted_copy(const std::vector<ObjectId>& ids) {
  std::vector<ObjectId> s = ids;
  std::sort(s.begin(), s.end());
  return s;
}

bool contains(const std::vector<ObjectId>& sorted, ObjectId id) { return std::binary_search(sorted.begin(), sorted.end(), id); }

// Per object index (mesh.hpp): whether the object is in `sorted_ids`.
std::vector<std::uint8_t> allowed_objects(const TriangleMesh& mesh, const std::vector<ObjectId>& sorted_ids) {
  std::vector<std::uint8_t> allowed(mesh.object_ids.size());
  for (std::size_t k = 0; k < allowed.size(); ++k) allowed[k] = contains(sorted_ids, mesh.object_ids[k]) ? 1 : 0;
  return allowed;
}

// Sizes of the 4-connected components of the set pixels of `mask`, found in row-major order.
std::vector<std::uint64_t> component_sizes(const std::vector<std::uint8_t>& mask, int width, int height) {
  std::vector<std::uint8_t> seen(mask.size(), 0);
  std::vector<std::size_t> stack;
  std::vector<std::uint64_t> sizes;
  for (std::size_t start = 0; start < mask.size(); ++start) {
    if (!mask[start] || seen[start]) continue;
    std::uint64_t size = 0;
    seen[start] = 1;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t p = stack.back();
      stack.pop_back();
      ++size;
      const int i = int(p % std::size_t(width)), j = int(p / std::size_t(width));
      auto visit = [&](int ni, int nj) {
        if (ni < 0 || nj < 0 || ni >= width || nj >= height) return;
        const std::size_t q = std::size_t(nj) * std::size_t(width) + std::size_t(ni);
        if (mask[q] && !seen[q]) seen[q] = 1, stack.push_back(q);
      };
      visit(i - 1, j), visit(i + 1, j), visit(i, j - 1), visit(i, j + 1);
    }
    sizes.push_back(size);
  }
  return sizes;
}

}  // namespace

WitnessRay pixel_ray(const Camera& camera, int i, int j) { return PixelRays(camera).ray(i, j); }

PixelOracle::PixelOracle(const RayOracle& rays) : rays_(rays) {}

IdImage PixelOracle::render(const Camera& camera, const std::vector<ObjectId>* only, int threads) const {
  validate(camera);
  const EmbreeScene& embree = rays_.embree();
  const TriangleMesh& mesh = embree.mesh();
  const PixelRays rays(camera);
  IdImage image;
  image.width = rays.resolution().width;
  image.height = rays.resolution().height;
  image.ids.assign(std::size_t(image.width) * std::size_t(image.height), kNoObject);
  const std::vector<std::uint8_t> allowed = only ? allowed_objects(mesh, sorted_copy(*only)) : std::vector<std::uint8_t>{};
  // A row's pixels in packets of neighbours, the most coherent rays there are.
  parallel_for(std::size_t(image.height), threads, 1, [&](std::size_t j) {
    const auto width = std::size_t(image.width);
    for (std::size_t first = 0; first < width; first += EmbreeScene::kPacket)
      cast_pixels(rays, embree, std::min(EmbreeScene::kPacket, width - first), [&](std::size_t k) { return j * width + first + k; },
                  only ? &allowed : nullptr, image.ids);
  });
  return image;
}

PixelComparison PixelOracle::compare(const Camera& camera, const std::vector<ObjectId>& pvs, int threads) const {
  return compare(render(camera, nullptr, threads), camera, pvs, threads);
}

PixelComparison PixelOracle::compare(const IdImage& full, const Camera& camera, const std::vector<ObjectId>& pvs,
                                     int threads) const {
  validate(camera);
  const PixelRays rays(camera);
  const Resolution res = rays.resolution();
  if (full.width != res.width || full.height != res.height || full.ids.size() != std::size_t(res.width) * std::size_t(res.height))
    throw std::invalid_argument("PixelOracle::compare: the full render does not have the camera's resolution");
  const EmbreeScene& embree = rays_.embree();
  const TriangleMesh& mesh = embree.mesh();
  const std::vector<ObjectId> in_pvs = sorted_copy(pvs);

  PixelComparison out;
  out.resolution = res;
  out.misdrawn_mask.assign(full.ids.size(), 0);
  out.drawn = full;
  // Only a pixel whose full-scene object X is NOT in the PVS can differ. Where X is in the PVS
  // (or the pixel is background), X's hit is the first hit of the pixel's ray among all objects,
  // so it is also the first among the PVS's objects (a subset that contains X): the PVS-only
  // buffer shows X too. Where X is not in the PVS, the PVS-only buffer shows a PVS object or the
  // background, never X, so the pixel differs. Hence misdrawn = "full id not in the PVS", and the
  // PVS-only rays are needed only for those pixels (to say what is drawn there instead).
  std::vector<std::size_t> misdrawn;
  for (std::size_t p = 0; p < full.ids.size(); ++p) {
    const ObjectId id = full.ids[p];
    if (id == kNoObject || contains(in_pvs, id)) continue;
    out.misdrawn_mask[p] = 1;
    misdrawn.push_back(p);
    ++out.misdrawn_by_object[id];
  }
  out.misdrawn_pixels = misdrawn.size();

  const std::vector<std::uint8_t> allowed = allowed_objects(mesh, in_pvs);
  // In packets of consecutive misdrawn pixels (row-major, so mostly neighbours in a blob).
  const std::size_t packets = (misdrawn.size() + EmbreeScene::kPacket - 1) / EmbreeScene::kPacket;
  parallel_for(packets, threads, 16, [&](std::size_t q) {
    const std::size_t first = q * EmbreeScene::kPacket;
    cast_pixels(rays, embree, std::min(EmbreeScene::kPacket, misdrawn.size() - first), [&](std::size_t k) { return misdrawn[first + k]; },
                &allowed, out.drawn.ids);
  });

  for (std::uint64_t size : component_sizes(out.misdrawn_mask, res.width, res.height)) {
    ++out.blobs;
    out.largest_blob = std::max(out.largest_blob, size);
  }

  // Witnesses: the first pixel of each culled object, in row-major order, whose ray (re-cast:
  // an IdImage keeps no triangles) hits that object inside the view volume in double precision.
  const ViewTransform& volume = rays.view();
  for (std::size_t p : misdrawn) {
    const ObjectId id = full.ids[p];
    if (out.witnesses.count(id)) continue;
    WitnessRay r = rays.ray(int(p % std::size_t(res.width)), int(p / std::size_t(res.width)));
    const EmbreeHit hit = embree.cast(to_float(r.origin - mesh.origin, r.direction, r.t_near, r.t_far));
    if (!hit.hit() || mesh.owner_id[hit.triangle] != id) continue;
    r.t_hit = embree.exact_t(r.origin, r.direction, hit);
    r.hit_point = r.origin + r.direction * r.t_hit;
    r.triangle = hit.triangle;
    if (volume.contains(r.hit_point)) out.witnesses.emplace(id, r);
  }
  return out;
}

}  // namespace cullcheck::oracle
