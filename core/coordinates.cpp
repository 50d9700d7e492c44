#include "core/coordinates.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/errors.hpp"

namespace cullcheck {
namespace {

// Shortest text that reads back to the same double, for messages.
std::string num(double v) { return nlohmann::json(v).dump(); }
std::string pair_text(Vec2 p) { return "[" + num(p.x) + ", " + num(p.y) + "]"; }

// a + b rounded once, and what the rounding lost (Knuth's TwoSum: the error is itself a double,
// and zero exactly when the sum is exact).
struct Sum {
  double value, error;
};
Sum two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
std::optional<double> exact_sum(double a, double b) {
  const Sum s = two_sum(a, b);
  if (s.error != 0.0 || !std::isfinite(s.value)) return std::nullopt;
  return s.value;
}

}  // namespace

const char* frame_name(CoordinateFrame frame) { return frame == CoordinateFrame::world ? "world" : "local"; }

CoordinateFrame parse_coordinate_frame(const std::string& text, const std::string& flag) {
  if (text == "local") return CoordinateFrame::local;
  if (text == "world") return CoordinateFrame::world;
  throw InputError("command line", flag, "must be world or local, got '" + text + "'");
}

CoordinateConversion to_scene_local(CameraPath& path, const Scene& scene, std::optional<CoordinateFrame> fallback,
                                    const std::string& file) {
  CoordinateConversion c;
  c.origin = scene.origin;
  c.declared_origin = path.origin;
  if (path.coordinates) {
    if (fallback && *fallback != *path.coordinates)
      throw InputError(file, "coordinates", std::string("says ") + frame_name(*path.coordinates) + " but --coordinates says " +
                                                frame_name(*fallback) + ": drop one of them");
    c.given = *path.coordinates;
    c.decided_by = "file";
  } else if (fallback) {
    c.given = *fallback;
    c.decided_by = "--coordinates";
  }
  // Local positions relative to the declared origin move by (declared - scene origin); world
  // ones by -origin, which is the same with a declared origin of (0, 0).
  Vec2 from{0.0, 0.0};
  if (c.given == CoordinateFrame::local) from = path.origin.value_or(scene.origin);
  const std::optional<double> dx = exact_sum(from.x, -scene.origin.x), dy = exact_sum(from.y, -scene.origin.y);
  if (!dx || !dy)
    throw InputError(file, "origin", "moving from origin " + pair_text(from) + " to the scene's origin " + pair_text(scene.origin) +
                                         " is not exact in double precision");
  for (std::size_t i = 0; i < path.frames.size(); ++i) {
    Vec3& p = path.frames[i].position;
    const Sum x = two_sum(p.x, *dx), y = two_sum(p.y, *dy);
    // World positions are as fine as doubles get there; a local one (finer near its origin) can
    // only be moved to another origin rounded, once, by less than half an ulp of the result.
    if ((x.error != 0.0 || y.error != 0.0) && c.given == CoordinateFrame::world)
      throw InputError(file, "frames[" + std::to_string(i) + "].position",
                       "[" + num(p.x) + ", " + num(p.y) + "] (world) minus the scene's origin " + pair_text(scene.origin) +
                           " would round in double precision: give this camera in scene-local coordinates");
    if (!std::isfinite(x.value) || !std::isfinite(y.value))
      throw InputError(file, "frames[" + std::to_string(i) + "].position", "is not finite once moved to the scene's origin");
    c.rounding_m = std::max({c.rounding_m, std::abs(x.error), std::abs(y.error)});
    c.moved = c.moved || x.value != p.x || y.value != p.y;
    p.x = x.value, p.y = y.value;
  }
  path.coordinates = CoordinateFrame::local;
  path.origin = scene.origin;
  return c;
}

double eye_margin(const Scene& scene) {
  const Box2 b = scene.bounds().plan();
  return std::max({1000.0, b.hi.x - b.lo.x, b.hi.y - b.lo.y});
}

void require_an_eye_near_the_scene(const CameraPath& path, const Scene& scene, const CoordinateConversion& how,
                                   const std::string& file) {
  if (scene.object_count() == 0 || path.frames.empty()) return;
  const Box2 b = scene.bounds().plan();
  const double m = eye_margin(scene);
  const Box2 grown{{b.lo.x - m, b.lo.y - m}, {b.hi.x + m, b.hi.y + m}};
  for (const Camera& c : path.frames)
    if (grown.contains(plan(c.position))) return;
  const Vec3 eye = path.frames.front().position;
  const bool one = path.frames.size() == 1;
  std::string hint;
  if (how.given == CoordinateFrame::world)
    hint = "it was given in world coordinates (" + std::string(how.decided_by == "file" ? "the file says so" : "--coordinates world") +
           "): is it for this scene?";
  else if (how.decided_by == "default")
    hint = "a file without \"coordinates\" is read as scene-local: if its positions are world coordinates, say \"coordinates\": "
           "\"world\" in it or give --coordinates world";
  else
    hint = "it was given in local coordinates (" + std::string(how.decided_by == "file" ? "the file says so" : "--coordinates local") +
           "): is it for this scene?";
  throw InputError(file, one ? "position" : "frames[0].position",
                   std::string(one ? "the eye" : "every eye of the path (" + std::to_string(path.frames.size()) + " frames)") +
                       " lies outside the scene's plan bounds grown by " + num(m) + " m, so it would see nothing: " +
                       (one ? "it is at " : "the first is at ") + "[" + num(eye.x) + ", " + num(eye.y) + ", " + num(eye.z) +
                       "] scene-local, the bounds are x [" + num(b.lo.x) + ", " + num(b.hi.x) + "], y [" + num(b.lo.y) + ", " +
                       num(b.hi.y) + "] scene-local, the origin is " + pair_text(scene.origin) + " (world = local + origin); " + hint);
}

std::string coordinates_line(const CoordinateConversion& c, const std::string& file) {
  if (c.decided_by == "generator")
    return "coordinates: scene-local metres, world = local + origin " + pair_text(c.origin) + "; " + file + " generated in them";
  std::string line = "coordinates: scene-local metres, world = local + origin " + pair_text(c.origin) + "; " + file + " given in " +
                     frame_name(c.given) + " coordinates (" +
                     (c.decided_by == "file"            ? std::string("said by the file")
                      : c.decided_by == "--coordinates" ? std::string("--coordinates")
                                                        : std::string("default: files that do not say are local")) +
                     ")";
  if (c.declared_origin) line += " relative to origin " + pair_text(*c.declared_origin);
  line += c.moved ? ", converted to scene-local" : ", used as they are";
  if (c.rounding_m > 0.0) line += " (rounded by at most " + num(c.rounding_m) + " m)";
  return line;
}

}  // namespace cullcheck
