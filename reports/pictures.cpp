#include "reports/pictures.hpp"

#include <spng.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/scene_io.hpp"

namespace cullcheck {
namespace {

bool in_sorted(const std::vector<ObjectId>& sorted, ObjectId id) { return std::binary_search(sorted.begin(), sorted.end(), id); }

std::vector<ObjectId> sorted_copy(std::vector<ObjectId> ids) {
  std::sort(ids.begin(), ids.end());
  return ids;
}

Rgb darker(Rgb c) { return {std::uint8_t(c.r * 3 / 5), std::uint8_t(c.g * 3 / 5), std::uint8_t(c.b * 3 / 5)}; }

struct SpngContext {
  spng_ctx* ctx;
  explicit SpngContext(int flags) : ctx(spng_ctx_new(flags)) {
    if (!ctx) throw std::runtime_error("libspng: cannot create a context");
  }
  ~SpngContext() { spng_ctx_free(ctx); }
  SpngContext(const SpngContext&) = delete;
  SpngContext& operator=(const SpngContext&) = delete;
};

void check_spng(int ret, const char* what) {
  if (ret != 0) throw std::runtime_error(std::string("libspng: ") + what + ": " + spng_strerror(ret));
}

// Plan-view drawing on an RgbImage through a MapFrame.
class Canvas {
 public:
  Canvas(RgbImage& image, const MapFrame& frame) : image_(image), frame_(frame) {}

  // Continuous pixel coordinates of a plan point (pixel (i, j) spans [i, i + 1) x [j, j + 1)).
  double fx(Vec2 p) const { return (p.x - frame_.extent.lo.x) / frame_.metres_per_pixel; }
  double fy(Vec2 p) const { return (frame_.extent.hi.y - p.y) / frame_.metres_per_pixel; }

  // Calls mark(i, j) for every pixel a segment from a to b crosses (sampled at half-pixel steps
  // after clipping to the image, so a line of any length costs at most the image's size).
  template <class Mark>
  void segment(Vec2 a, Vec2 b, Mark&& mark) const {
    double x0 = fx(a), y0 = fy(a), x1 = fx(b), y1 = fy(b);
    // Liang-Barsky clipping against [0, width] x [0, height].
    double t0 = 0.0, t1 = 1.0;
    const double dx = x1 - x0, dy = y1 - y0;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {x0, frame_.width - x0, y0, frame_.height - y0};
    for (int k = 0; k < 4; ++k) {
      if (p[k] == 0.0) {
        if (q[k] < 0.0) return;
        continue;
      }
      const double t = q[k] / p[k];
      if (p[k] < 0.0) t0 = std::max(t0, t);
      else t1 = std::min(t1, t);
    }
    if (t0 > t1) return;
    const double ax = x0 + dx * t0, ay = y0 + dy * t0, bx = x0 + dx * t1, by = y0 + dy * t1;
    const int steps = 1 + int(std::ceil(2.0 * std::max(std::abs(bx - ax), std::abs(by - ay))));
    for (int s = 0; s <= steps; ++s) {
      const double t = double(s) / steps;
      const int i = std::clamp(int(std::floor(ax + (bx - ax) * t)), 0, frame_.width - 1);
      const int j = std::clamp(int(std::floor(ay + (by - ay) * t)), 0, frame_.height - 1);
      mark(i, j);
    }
  }

  void line(Vec2 a, Vec2 b, Rgb c) {
    segment(a, b, [&](int i, int j) { image_.set(i, j, c); });
  }

  // Pixels whose centres the plan box may hold.
  void pixel_range(const Box2& box, int& i0, int& i1, int& j0, int& j1) const {
    i0 = std::max(0, int(std::floor(fx(box.lo))) - 1);
    i1 = std::min(frame_.width - 1, int(std::floor(fx(box.hi))) + 1);
    j0 = std::max(0, int(std::floor(fy(box.hi))) - 1);
    j1 = std::min(frame_.height - 1, int(std::floor(fy(box.lo))) + 1);
  }

 private:
  RgbImage& image_;
  const MapFrame& frame_;
};

bool inside_polygon(const std::vector<Vec2>& ring, Vec2 p) {
  bool inside = false;  // crossing number
  for (std::size_t k = 0, n = ring.size(); k < n; ++k) {
    const Vec2 a = ring[k], b = ring[(k + 1) % n];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
  }
  return inside;
}

bool inside_triangle(Vec2 a, Vec2 b, Vec2 c, Vec2 p) {
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  return (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
}

// Whether the vertical segment above plan point p, z in [z0, z1], meets the view volume.
bool column_meets(const ViewVolume& v, Vec2 p, double z0, double z1) {
  if (v.omnidirectional) {
    const double dx = p.x - v.eye.x, dy = p.y - v.eye.y;
    const double dz = std::max({z0 - v.eye.z, 0.0, v.eye.z - z1});
    return dx * dx + dy * dy + dz * dz <= v.far * v.far;
  }
  double lo = z0, hi = z1;
  for (int k = 0; k < v.plane_count; ++k) {
    const Plane& pl = v.planes[k];
    const double c = -(pl.n.x * p.x + pl.n.y * p.y + pl.d);  // need n.z * z >= c
    if (pl.n.z > 0) lo = std::max(lo, c / pl.n.z);
    else if (pl.n.z < 0) hi = std::min(hi, c / pl.n.z);
    else if (c > 0) return false;
  }
  return lo <= hi;
}

}  // namespace

RgbImage::RgbImage(int w, int h, Rgb fill) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3) {
  for (std::size_t k = 0; k < rgb.size(); k += 3) rgb[k] = fill.r, rgb[k + 1] = fill.g, rgb[k + 2] = fill.b;
}

Rgb RgbImage::at(int i, int j) const {
  const std::size_t k = 3 * (std::size_t(j) * std::size_t(width) + std::size_t(i));
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

void RgbImage::set(int i, int j, Rgb c) {
  if (i < 0 || j < 0 || i >= width || j >= height) return;
  const std::size_t k = 3 * (std::size_t(j) * std::size_t(width) + std::size_t(i));
  rgb[k] = c.r, rgb[k + 1] = c.g, rgb[k + 2] = c.b;
}

void write_png(const RgbImage& image, const std::string& path) { write_text_file_atomically(path, encode_png(image)); }

std::string encode_png(const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
    throw std::invalid_argument("write_png: image size and pixel buffer disagree");
  SpngContext s(SPNG_CTX_ENCODER);
  check_spng(spng_set_option(s.ctx, SPNG_ENCODE_TO_BUFFER, 1), "set option");
  spng_ihdr ihdr{};
  ihdr.width = std::uint32_t(image.width);
  ihdr.height = std::uint32_t(image.height);
  ihdr.bit_depth = 8;
  ihdr.color_type = SPNG_COLOR_TYPE_TRUECOLOR;
  check_spng(spng_set_ihdr(s.ctx, &ihdr), "set header");
  check_spng(spng_encode_image(s.ctx, image.rgb.data(), image.rgb.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE), "encode");
  std::size_t size = 0;
  int error = 0;
  std::unique_ptr<void, decltype(&std::free)> png(spng_get_png_buffer(s.ctx, &size, &error), &std::free);
  check_spng(error, "get buffer");
  if (!png) throw std::runtime_error("libspng: no PNG buffer");
  return std::string(static_cast<const char*>(png.get()), size);
}

RgbImage read_png(const std::string& path) {
  const std::string bytes = read_text_file(path);
  SpngContext s(0);
  auto fail = [&](int ret) {
    if (ret != 0) throw InputError("file " + path, "(png)", std::string("not a readable PNG: ") + spng_strerror(ret));
  };
  fail(spng_set_png_buffer(s.ctx, bytes.data(), bytes.size()));
  spng_ihdr ihdr{};
  fail(spng_get_ihdr(s.ctx, &ihdr));
  std::size_t size = 0;
  fail(spng_decoded_image_size(s.ctx, SPNG_FMT_RGB8, &size));
  RgbImage image;
  image.width = int(ihdr.width);
  image.height = int(ihdr.height);
  image.rgb.resize(size);
  fail(spng_decode_image(s.ctx, image.rgb.data(), size, SPNG_FMT_RGB8, 0));
  return image;
}

Vec2 MapFrame::centre_of(int i, int j) const {
  return {extent.lo.x + (i + 0.5) * metres_per_pixel, extent.hi.y - (j + 0.5) * metres_per_pixel};
}

void MapFrame::pixel_of(Vec2 p, int& i, int& j) const {
  i = int(std::floor((p.x - extent.lo.x) / metres_per_pixel));
  j = int(std::floor((extent.hi.y - p.y) / metres_per_pixel));
}

MapFrame map_frame(const Scene& scene, const Camera& camera, int size_px) {
  Box2 box = scene.bounds().plan();
  box.extend(plan(camera.position));
  return map_frame_of(box, size_px);
}

MapFrame map_frame_of(Box2 box, int size_px) {
  size_px = std::max(size_px, 16);
  const double span = std::max(box.hi.x - box.lo.x, box.hi.y - box.lo.y);
  const double margin = std::max(1.0, 0.04 * span);
  box.lo = box.lo - Vec2{margin, margin};
  box.hi = box.hi + Vec2{margin, margin};
  const double w = box.hi.x - box.lo.x, h = box.hi.y - box.lo.y;
  MapFrame f;
  f.metres_per_pixel = std::max(w, h) / size_px;
  f.width = w >= h ? size_px : std::max(1, int(std::ceil(w / f.metres_per_pixel)));
  f.height = h > w ? size_px : std::max(1, int(std::ceil(h / f.metres_per_pixel)));
  // Centre the box in the whole pixels.
  const Vec2 centre = box.center(), half{f.width * f.metres_per_pixel / 2, f.height * f.metres_per_pixel / 2};
  f.extent = {centre - half, centre + half};
  return f;
}

RgbImage top_down_map(const Scene& scene, const Camera& camera, const std::vector<ObjectId>& pvs_ids,
                      const std::vector<ObjectId>& seen_ids, const std::vector<ObjectId>& missed_ids,
                      const std::vector<oracle::WitnessRay>& witness_rays, int size_px) {
  return top_down_map(scene, camera, pvs_ids, seen_ids, missed_ids, witness_rays, map_frame(scene, camera, size_px));
}

RgbImage top_down_map(const Scene& scene, const Camera& camera, const std::vector<ObjectId>& pvs_ids,
                      const std::vector<ObjectId>& seen_ids, const std::vector<ObjectId>& missed_ids,
                      const std::vector<oracle::WitnessRay>& witness_rays, const MapFrame& frame) {
  namespace colours = map_colours;
  RgbImage image(frame.width, frame.height, colours::kBackground);
  Canvas canvas(image, frame);
  const std::vector<ObjectId> pvs = sorted_copy(pvs_ids), seen = sorted_copy(seen_ids), missed = sorted_copy(missed_ids);

  // The view volume's plan footprint within the scene's bounds.
  if (scene.object_count() > 0) {
    const Box3 bounds = scene.bounds();
    const Box2 plan_box = bounds.plan();
    const double z0 = std::min(0.0, bounds.lo.z), z1 = std::max(bounds.hi.z, z0);
    const ViewVolume volume(camera);
    std::vector<std::uint8_t> in(std::size_t(frame.width) * std::size_t(frame.height), 0);
    for (int j = 0; j < frame.height; ++j)
      for (int i = 0; i < frame.width; ++i) {
        const Vec2 p = frame.centre_of(i, j);
        in[std::size_t(j) * std::size_t(frame.width) + std::size_t(i)] = plan_box.contains(p) && column_meets(volume, p, z0, z1);
      }
    auto at = [&](int i, int j) {
      return i >= 0 && j >= 0 && i < frame.width && j < frame.height && in[std::size_t(j) * std::size_t(frame.width) + std::size_t(i)];
    };
    for (int j = 0; j < frame.height; ++j)
      for (int i = 0; i < frame.width; ++i)
        if (at(i, j))
          image.set(i, j, at(i - 1, j) && at(i + 1, j) && at(i, j - 1) && at(i, j + 1) ? colours::kViewVolume : colours::kViewVolumeEdge);
  }

  // Objects by class; each class over the last, so a missed object is never covered.
  enum Class { culled, over_estimate, visible, missed_class };
  auto class_of = [&](ObjectId id) {
    const bool in_pvs = in_sorted(pvs, id), is_seen = in_sorted(seen, id);
    if (in_sorted(missed, id) || (is_seen && !in_pvs)) return missed_class;
    if (in_pvs) return is_seen ? visible : over_estimate;
    return culled;
  };
  const Rgb fills[4] = {colours::kCulled, colours::kOverEstimate, colours::kVisible, colours::kMissed};
  std::vector<std::uint8_t> mask(std::size_t(frame.width) * std::size_t(frame.height), 0);
  // Fills the pixels `covered` marks in the box, outlines the marked pixels on the set's edge.
  auto paint = [&](const Box2& box, Rgb fill, auto&& mark) {
    int i0, i1, j0, j1;
    canvas.pixel_range(box, i0, i1, j0, j1);
    if (i0 > i1 || j0 > j1) return;
    auto idx = [&](int i, int j) { return std::size_t(j) * std::size_t(frame.width) + std::size_t(i); };
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) mask[idx(i, j)] = 0;
    mark([&](int i, int j) { mask[idx(i, j)] = 1; }, i0, i1, j0, j1);
    auto on = [&](int i, int j) { return i >= i0 && j >= j0 && i <= i1 && j <= j1 && mask[idx(i, j)]; };
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        if (on(i, j)) image.set(i, j, on(i - 1, j) && on(i + 1, j) && on(i, j - 1) && on(i, j + 1) ? fill : darker(fill));
  };
  for (int cls = culled; cls <= missed_class; ++cls) {
    for (const Building& b : scene.buildings) {
      if (class_of(b.id) != cls) continue;
      paint(b.bounds.plan(), fills[cls], [&](auto&& set, int i0, int i1, int j0, int j1) {
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i)
            if (inside_polygon(b.footprint, frame.centre_of(i, j))) set(i, j);
        for (std::size_t k = 0, n = b.footprint.size(); k < n; ++k)
          canvas.segment(b.footprint[k], b.footprint[(k + 1) % n], set);
      });
    }
    for (const MeshObject& m : scene.meshes) {
      if (class_of(m.id) != cls) continue;
      paint(m.bounds.plan(), fills[cls], [&](auto&& set, int i0, int i1, int j0, int j1) {
        for (const auto& t : m.triangles) {
          const Vec2 a = plan(m.vertices[t[0]]), b = plan(m.vertices[t[1]]), c = plan(m.vertices[t[2]]);
          Box2 tb;
          tb.extend(a), tb.extend(b), tb.extend(c);
          int ti0, ti1, tj0, tj1;
          canvas.pixel_range(tb, ti0, ti1, tj0, tj1);
          for (int j = std::max(j0, tj0); j <= std::min(j1, tj1); ++j)
            for (int i = std::max(i0, ti0); i <= std::min(i1, ti1); ++i)
              if (inside_triangle(a, b, c, frame.centre_of(i, j))) set(i, j);
          // Edges too, so faces seen edge-on from above (walls) still show.
          canvas.segment(a, b, set), canvas.segment(b, c, set), canvas.segment(c, a, set);
        }
      });
    }
  }

  for (const oracle::WitnessRay& r : witness_rays) canvas.line(plan(r.origin), plan(r.hit_point), colours::kWitnessRay);

  // The eye: a disc, and a tick along the view direction's plan component.
  const int radius = std::max(2, std::max(frame.width, frame.height) / 150);
  int ei, ej;
  frame.pixel_of(plan(camera.position), ei, ej);
  for (int dj = -radius; dj <= radius; ++dj)
    for (int di = -radius; di <= radius; ++di)
      if (di * di + dj * dj <= radius * radius) image.set(ei + di, ej + dj, colours::kEye);
  if (!camera.omnidirectional()) {
    const Vec3 f = basis_of(camera).forward;
    const double len = std::hypot(f.x, f.y);
    if (len > 1e-9) {
      const double reach = 4.0 * radius * frame.metres_per_pixel / len;
      canvas.line(plan(camera.position), plan(camera.position) + Vec2{f.x, f.y} * reach, colours::kEye);
    }
  }
  return image;
}

Rgb false_colour(ObjectId id) {
  // SplitMix64's finaliser: neighbouring ids get unrelated colours.
  std::uint64_t z = std::uint64_t(id) + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  auto channel = [&](int shift) { return std::uint8_t(48 + ((z >> shift) & 0xFF) * 175 / 255); };
  return {channel(0), channel(8), channel(16)};
}

RgbImage frame_image(const oracle::IdImage& full, const oracle::PixelComparison& comparison) {
  if (comparison.resolution.width != full.width || comparison.resolution.height != full.height ||
      comparison.misdrawn_mask.size() != full.ids.size())
    throw std::invalid_argument("frame_image: the id buffer and the comparison have different resolutions");
  RgbImage image(full.width, full.height, kFrameBackground);
  for (int j = 0; j < full.height; ++j)
    for (int i = 0; i < full.width; ++i) {
      const std::size_t p = std::size_t(j) * std::size_t(full.width) + std::size_t(i);
      if (comparison.misdrawn_mask[p]) image.set(i, j, kMisdrawn);
      else if (full.ids[p] != oracle::kNoObject) image.set(i, j, false_colour(full.ids[p]));
    }
  return image;
}

}  // namespace cullcheck
