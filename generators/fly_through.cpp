// 6-DoF fly-through over any scene (see camera_paths.hpp).
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "generators/angles.hpp"
#include "generators/camera_paths.hpp"
#include "generators/footprint_shapes.hpp"
#include "generators/open_space.hpp"
#include "generators/param_checks.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {
namespace {

constexpr std::uint64_t kFlyStream = 0x464C5954;  // "FLYT"

struct Waypoint {
  Vec2 position;
  double altitude = 0.0;
};

// A plan-view curve sampled densely, with arc length, so frames can be spaced by speed.
struct SampledCurve {
  std::vector<Vec2> points;
  std::vector<double> arc;        // cumulative length at each point
  std::vector<double> altitude;   // planned altitude at each point
};

Vec2 catmull_rom(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3, double t) {
  const double t2 = t * t, t3 = t2 * t;
  return (p1 * 2.0 + (p2 - p0) * t + (p0 * 2.0 - p1 * 5.0 + p2 * 4.0 - p3) * t2 + (p1 * 3.0 - p0 - p2 * 3.0 + p3) * t3) * 0.5;
}

// Uniform Catmull-Rom through the waypoints (it passes through each one); the planned altitude
// eases between consecutive waypoints' altitudes.
SampledCurve sample_curve(const std::vector<Waypoint>& w) {
  SampledCurve c;
  auto at = [&](long i) { return w[static_cast<std::size_t>(std::clamp<long>(i, 0, static_cast<long>(w.size()) - 1))].position; };
  c.points.push_back(w[0].position), c.arc.push_back(0.0), c.altitude.push_back(w[0].altitude);
  for (std::size_t i = 0; i + 1 < w.size(); ++i) {
    const long k = static_cast<long>(i);
    const int n = std::max(8, static_cast<int>(std::ceil(length(w[i + 1].position - w[i].position) / 0.25)));
    for (int s = 1; s <= n; ++s) {
      const double t = static_cast<double>(s) / n;
      const Vec2 p = catmull_rom(at(k - 1), at(k), at(k + 1), at(k + 2), t);
      c.arc.push_back(c.arc.back() + length(p - c.points.back()));
      c.points.push_back(p);
      c.altitude.push_back(w[i].altitude + (w[i + 1].altitude - w[i].altitude) * smoothstep(t));
    }
  }
  return c;
}

// Values at keyframes every 1-3 s, eased between: the pitch, roll and look-around profiles.
class KeyframeTrack {
 public:
  template <class Draw>
  KeyframeTrack(Random& rng, int frames, double fps, Draw&& draw) {
    int f = 0;
    keys_.push_back({0, draw()});
    while (f < frames) {
      f += static_cast<int>(std::max<std::int64_t>(1, rng.uniform_int(static_cast<std::int64_t>(fps), static_cast<std::int64_t>(3 * fps))));
      keys_.push_back({f, draw()});
    }
  }
  double at(int frame) const {
    std::size_t i = 0;
    while (i + 2 < keys_.size() && keys_[i + 1].frame <= frame) ++i;
    const Key& a = keys_[i];
    const Key& b = keys_[i + 1];
    return a.value + (b.value - a.value) * smoothstep(static_cast<double>(frame - a.frame) / (b.frame - a.frame));
  }

 private:
  struct Key {
    int frame;
    double value;
  };
  std::vector<Key> keys_;
};

double round_to(double v, double quantum) { return std::round(v / quantum) * quantum; }

}  // namespace

void validate(const FlyThroughParams& p) {
  const ParamChecks check("path", "fly_through");
  check.in_range("frames", p.frames, 1, 1'000'000);
  check.above("frames_per_second", p.frames_per_second, 0.0, 1000.0);
  check.above("cruise_speed", p.cruise_speed, 0.0, 1000.0);
  check.above("street_speed", p.street_speed, 0.0, p.cruise_speed);
  check.in_range("rooftop_margin", p.rooftop_margin, 0.0, 1.0e4);
  check.above("street_eye_height", p.street_eye_height, 0.0, 1000.0);
  check.in_range("dip_fraction", p.dip_fraction, 0.0, 1.0);
  // A positive clearance keeps the eye strictly off roofs and walls (closed prisms).
  check.in_range("clearance", p.clearance, 0.01, 100.0);
  check.in_range("min_pitch_deg", p.min_pitch_deg, -90.0, 90.0);
  check.in_range("max_pitch_deg", p.max_pitch_deg, p.min_pitch_deg, 90.0);
  check.in_range("max_roll_deg", p.max_roll_deg, 0.0, 180.0);
  check.above("max_turn_rate_deg", p.max_turn_rate_deg, 0.0, 1.0e5);
  if (p.hfov_deg != 360.0 && !(p.hfov_deg > 0.0 && p.hfov_deg < 180.0))
    check.fail("hfov_deg", "must lie in (0, 180) or be 360 (omnidirectional) (got " + ParamChecks::text(p.hfov_deg) + ")");
  if (!(p.vfov_deg > 0.0 && p.vfov_deg < 180.0)) check.fail("vfov_deg", "must lie in (0, 180)");
}

CameraPath fly_through(const Scene& scene, const FlyThroughParams& p, std::uint64_t seed) {
  validate(p);
  const OpenSpace open(scene);
  const Box3 bounds = open.bounds();
  const bool empty = scene.buildings.empty();
  const Box2 area = empty ? Box2{{-100, -100}, {100, 100}} : bounds.plan();
  const double top = empty ? 0.0 : bounds.hi.z;
  const double cruise = top + p.rooftop_margin;
  Random rng = Random::stream(seed, kFlyStream);

  // Waypoints 40-150 m apart (less in a small scene) inside the scene's plan bounds, each
  // within 90 degrees of the previous leg's direction so the curve has no cusps, until the path
  // is long enough for every frame at cruise speed (the curve through them is at least as long
  // as its chords).
  const double span = std::max({area.hi.x - area.lo.x, area.hi.y - area.lo.y, 20.0});
  const double leg_min = std::min(40.0, span / 4), leg_max = std::min(150.0, span / 2);
  auto random_point = [&] { return Vec2{rng.uniform_real(area.lo.x, area.hi.x), rng.uniform_real(area.lo.y, area.hi.y)}; };
  auto unit = [](Vec2 v) { const double l = length(v); return l > 0 ? v * (1.0 / l) : Vec2{1, 0}; };
  const double needed = p.frames * p.cruise_speed / p.frames_per_second + 1.0;
  std::vector<Waypoint> waypoints{{random_point(), cruise + rng.uniform_real(0.0, p.rooftop_margin)}};
  // Drawn one at a time: a call's arguments are evaluated in an unspecified order (gcc right to
  // left, clang left to right), so two draws as arguments gave a clang build another path for the
  // same seed. gcc's order is kept: the quadrant first.
  const int quadrant = static_cast<int>(rng.uniform_int(0, 3));
  const double half_tangent = rng.uniform_real(-1, 1);
  const PlanarRotation first = rotation_from_half_tangent(half_tangent, quadrant);
  Vec2 leg_dir{first.cos, first.sin};
  double chords = 0.0;
  while (chords < needed && waypoints.size() < 1'000'000) {
    const Vec2 from = waypoints.back().position;
    const bool want_dip = rng.bernoulli(p.dip_fraction);
    std::optional<Waypoint> next;
    // A street-level waypoint must be in the open, with room around it; if none is found, the
    // waypoint stays at cruise altitude.
    for (int attempt = 0; attempt < 64 && !next; ++attempt) {
      const bool dip = want_dip && attempt < 32;
      const Vec2 dir = unit(rotate(leg_dir, rotation_from_half_tangent(rng.uniform_real(-1, 1))));
      const Vec2 q = from + dir * rng.uniform_real(leg_min, leg_max);
      if (!area.contains(q)) continue;
      if (dip && !open.is_open(q, p.clearance + 1.0)) continue;
      next = Waypoint{q, dip ? p.street_eye_height : cruise + rng.uniform_real(0.0, p.rooftop_margin)};
    }
    if (!next) next = Waypoint{random_point(), cruise + rng.uniform_real(0.0, p.rooftop_margin)};  // rare: cornered
    const double chord = length(next->position - from);
    if (chord > 0.0) leg_dir = unit(next->position - from);
    chords += chord;
    waypoints.push_back(*next);
  }
  const SampledCurve curve = sample_curve(waypoints);

  // March along the curve at a speed that eases from street_speed near the ground to
  // cruise_speed at cruise altitude.
  const int n = p.frames;
  std::vector<Vec2> plan_pos(n);
  std::vector<double> planned(n);
  double s = 0.0;
  std::size_t seg = 0;
  for (int f = 0; f < n; ++f) {
    while (seg + 2 < curve.arc.size() && curve.arc[seg + 1] < s) ++seg;
    const double a0 = curve.arc[seg], a1 = curve.arc[std::min(seg + 1, curve.arc.size() - 1)];
    const double t = a1 > a0 ? std::clamp((s - a0) / (a1 - a0), 0.0, 1.0) : 0.0;
    const std::size_t seg1 = std::min(seg + 1, curve.points.size() - 1);
    plan_pos[f] = curve.points[seg] + (curve.points[seg1] - curve.points[seg]) * t;
    planned[f] = curve.altitude[seg] + (curve.altitude[seg1] - curve.altitude[seg]) * t;
    const double lift = cruise > p.street_eye_height ? std::clamp((planned[f] - p.street_eye_height) / (cruise - p.street_eye_height), 0.0, 1.0) : 1.0;
    s += (p.street_speed + (p.cruise_speed - p.street_speed) * lift) / p.frames_per_second;
  }

  // Clearance: the least safe altitude per frame, then a moving maximum and a moving average
  // over the same window. Each averaged term is a maximum over a window that contains the
  // frame itself, so the result never drops below that frame's least safe altitude.
  std::vector<double> least(n), widened(n), z(n);
  for (int f = 0; f < n; ++f) {
    const double roof = open.roof_height_near(plan_pos[f], p.clearance);
    least[f] = roof > 0.0 ? roof + p.clearance : 0.0;
  }
  const int w = std::max(1, static_cast<int>(p.frames_per_second / 3));
  for (int f = 0; f < n; ++f) {
    double m = 0.0;
    for (int k = std::max(0, f - w); k <= std::min(n - 1, f + w); ++k) m = std::max(m, least[k]);
    widened[f] = std::max(planned[f], m);
  }
  for (int f = 0; f < n; ++f) {
    double sum = 0.0;
    int count = 0;
    for (int k = std::max(0, f - w); k <= std::min(n - 1, f + w); ++k) sum += widened[k], ++count;
    z[f] = std::max(sum / count, least[f]);
  }

  // Orientation: heading from a half-second look-ahead plus an eased look-around offset; pitch
  // keyframes reach down to min_pitch (looking almost straight down at the streets) a quarter
  // of the time; roll keyframes within +-max_roll.
  const double min_pitch = radians(p.min_pitch_deg), max_pitch = radians(p.max_pitch_deg), max_roll = radians(p.max_roll_deg);
  const KeyframeTrack look(rng, n, p.frames_per_second, [&] { return rng.uniform_real(-radians(40), radians(40)); });
  const KeyframeTrack pitch(rng, n, p.frames_per_second,
                            [&] { return rng.bernoulli(0.25) ? min_pitch : rng.uniform_real(min_pitch, max_pitch); });
  const KeyframeTrack roll(rng, n, p.frames_per_second, [&] { return rng.uniform_real(-max_roll, max_roll); });
  const int ahead = std::max(1, static_cast<int>(p.frames_per_second / 2));
  const double max_turn = radians(p.max_turn_rate_deg) / p.frames_per_second;
  double heading = 0.0;  // unwrapped
  bool have_heading = false;

  CameraPath path;
  path.kind = "fly_through";
  path.seed = seed;
  path.frames_per_second = p.frames_per_second;
  path.frames.reserve(n);
  for (int f = 0; f < n; ++f) {
    // Near the end the look-ahead window slides back so it keeps its length.
    const int from = std::min(f, std::max(0, n - 1 - ahead));
    const Vec2 d = plan_pos[std::min(n - 1, from + ahead)] - plan_pos[from];
    if (length(d) > 1e-6) {
      // Follow the direction of travel at a bounded turn rate, so that even a sharp bend of the
      // curve turns the view smoothly.
      const double a = azimuth_of(d);
      heading = have_heading ? heading + std::clamp(shortest_turn(heading, a), -max_turn, max_turn) : a;
      have_heading = true;
    }
    Camera c;
    c.position = {round_to(plan_pos[f].x, 1e-6), round_to(plan_pos[f].y, 1e-6), std::ceil(z[f] * 1e6) / 1e6};
    c.yaw = wrap_azimuth(round_to(heading + look.at(f), 1e-9));
    c.pitch = std::clamp(round_to(pitch.at(f), 1e-9), -kPi / 2, kPi / 2);
    c.roll = round_to(roll.at(f), 1e-9);
    c.hfov = p.hfov_deg >= 360.0 ? kTwoPi : radians(p.hfov_deg);
    c.vfov = radians(p.vfov_deg);
    path.frames.push_back(c);
  }
  return path;
}

}  // namespace cullcheck::generators
