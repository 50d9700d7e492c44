// Pedestrian street walk on a Manhattan grid (see camera_paths.hpp).
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "generators/angles.hpp"
#include "generators/camera_paths.hpp"
#include "generators/manhattan_layout.hpp"
#include "generators/param_checks.hpp"
#include "generators/random.hpp"
#include "generators/walk_segments.hpp"

namespace cullcheck::generators {
namespace {

constexpr std::uint64_t kWalkStream = 0x57414C4B;  // "WALK"
constexpr int kStrideFrames = 36;                  // one sway period: a pair of steps, ~1.2 s

// Headings are the four street directions, counter-clockwise from east: azimuth = h * pi/2.
constexpr Vec2 kHeadingDir[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
double heading_yaw(int h) { return h * (kPi / 2); }

class Walker {
 public:
  Walker(const ManhattanLayout& layout, const StreetWalkParams& p, Random& rng)
      : layout_(layout), p_(p), rng_(rng), step_(p.walking_speed / p.frames_per_second),
        max_offset_(layout.street_width() / 2 - p.street_margin) {
    base_.position.z = p.eye_height;
    base_.hfov = p.hfov_deg >= 360.0 ? kTwoPi : radians(p.hfov_deg);
    base_.vfov = radians(p.vfov_deg);
    start();
  }

  std::vector<Camera> run() {
    frames_.reserve(p_.frames);
    emit();
    while (!done()) {
      const WalkSegment s = next_walk_segment(p_, rng_, max_offset_);
      switch (s.kind) {
        case WalkKind::forward: forward(s.frames); break;
        case WalkKind::backward: backward(s.frames); break;
        case WalkKind::sidestep: sidestep(s.metres); break;
        case WalkKind::stop: stop(s.frames); break;
      }
    }
    return std::move(frames_);
  }

 private:
  bool done() const { return static_cast<int>(frames_.size()) >= p_.frames; }

  void emit() {
    Camera c = base_;
    c.position.x = pos_.x, c.position.y = pos_.y;
    c.yaw = wrap_azimuth(yaw_);
    frames_.push_back(c);
  }

  // Lines across the current heading: x = const when walking east/west, y = const otherwise.
  double cross_line(int k) const { return horizontal() ? layout_.street_x(k) : layout_.street_y(k); }
  int cross_line_count() const { return horizontal() ? layout_.blocks_x + 1 : layout_.blocks_y + 1; }
  bool horizontal() const { return heading_ % 2 == 0; }
  double along() const { return horizontal() ? pos_.x : pos_.y; }
  // Signed distance from the centre line of the street being walked (left of east/north is +).
  double offset_of(Vec2 q) const { return horizontal() ? q.y - layout_.street_y(line_) : q.x - layout_.street_x(line_); }
  double offset() const { return offset_of(pos_); }
  // The direction in which offset() grows: north on east-west streets, east on north-south ones.
  Vec2 positive_side() const { return horizontal() ? Vec2{0, 1} : Vec2{1, 0}; }
  int sign() const { return heading_ < 2 ? +1 : -1; }  // +1 walking towards larger coordinates

  // Starts a few metres before an intersection, so that even a short path turns early.
  void start() {
    heading_ = static_cast<int>(rng_.uniform_int(0, 3));
    const int lines_along = horizontal() ? layout_.blocks_y + 1 : layout_.blocks_x + 1;
    line_ = static_cast<int>(rng_.uniform_int(0, lines_along - 1));
    // The target crossing must have one behind it, so start on a block's length.
    const int n = cross_line_count();
    target_ = sign() > 0 ? static_cast<int>(rng_.uniform_int(1, n - 1)) : static_cast<int>(rng_.uniform_int(0, n - 2));
    const double before = std::min(rng_.uniform_real(2.0, 20.0), std::abs(cross_line(target_) - cross_line(target_ - sign())) / 2);
    const double a = cross_line(target_) - sign() * before;
    const double centre = horizontal() ? layout_.street_y(line_) : layout_.street_x(line_);
    pos_ = horizontal() ? Vec2{a, centre} : Vec2{centre, a};
    yaw_ = heading_yaw(heading_);
  }

  // Forward with sway: each frame moves exactly one step, split between the heading and the
  // sideways direction, the sideways share following a smooth wave and reflecting at the
  // street margin.
  void forward(int frames) {
    const Vec2 dir = kHeadingDir[heading_], left = kHeadingDir[(heading_ + 1) % 4];
    for (int k = 0; k < frames && !done(); ++k) {
      double s = p_.sway * parabolic_wave(sway_phase_);
      sway_phase_ += 1.0 / kStrideFrames;
      auto moved = [&](double share) { return pos_ + dir * (step_ * std::sqrt(1.0 - share * share)) + left * (step_ * share); };
      if (s != 0.0 && std::abs(offset_of(moved(s))) > max_offset_) s = -s;
      if (s != 0.0 && std::abs(offset_of(moved(s))) > max_offset_) s = 0.0;
      pos_ = moved(s);
      emit();
      if ((along() - cross_line(target_)) * sign() >= 0.0) {
        at_intersection();
        return;
      }
    }
  }

  // Backward: facing the heading, stepping back, but never past the outermost street.
  void backward(int frames) {
    const double limit = sign() > 0 ? cross_line(0) : cross_line(cross_line_count() - 1);
    const int room = static_cast<int>(std::floor(std::abs(along() - limit) / step_));
    const Vec2 back = kHeadingDir[(heading_ + 2) % 4];
    for (int k = 0; k < std::min(frames, room) && !done(); ++k) {
      pos_ = pos_ + back * step_;
      emit();
    }
  }

  // Sideways to a new offset across the street, facing the heading: whole steps only, so the
  // walker stops up to one step short of the drawn offset.
  void sidestep(double target_offset) {
    const double delta = target_offset - offset();
    const Vec2 side = positive_side() * (delta > 0 ? 1.0 : -1.0);
    const int n = static_cast<int>(std::floor(std::abs(delta) / step_));
    for (int k = 0; k < n && !done(); ++k) {
      pos_ = pos_ + side * step_;
      emit();
    }
  }

  // Standing still; half the time looking around (a pure turn of the view direction, the ΔH
  // case of thesis ch. 3.1.3 step 5) and back.
  void stop(int frames) {
    const double look = rng_.bernoulli(0.5) ? rng_.uniform_real(radians(15), radians(60)) * (rng_.bernoulli(0.5) ? 1 : -1) : 0.0;
    const double base = yaw_;
    for (int k = 1; k <= frames && !done(); ++k) {
      const double t = static_cast<double>(k) / frames;
      yaw_ = base + look * (t < 0.5 ? smoothstep(2 * t) : smoothstep(2 - 2 * t));
      emit();
    }
    yaw_ = base;
  }

  // Chooses the next street (straight on, left, right, or rarely back) among those that lead to
  // another crossing, then turns in place.
  void at_intersection() {
    // The crossing we are at, in both index directions.
    const int col = horizontal() ? target_ : line_;
    const int row = horizontal() ? line_ : target_;
    struct Option { int heading; double weight; };
    const Option options[4] = {{heading_, 0.4}, {(heading_ + 1) % 4, 0.25}, {(heading_ + 3) % 4, 0.25}, {(heading_ + 2) % 4, 0.1}};
    auto leads_on = [&](int h) {
      switch (h) {
        case 0: return col + 1 <= layout_.blocks_x;
        case 1: return row + 1 <= layout_.blocks_y;
        case 2: return col - 1 >= 0;
        default: return row - 1 >= 0;
      }
    };
    double total = 0;
    for (const Option& o : options) total += leads_on(o.heading) ? o.weight : 0.0;
    double pick = rng_.uniform01() * total;
    int chosen = options[3].heading;  // a U-turn always leads on
    for (const Option& o : options) {
      if (!leads_on(o.heading)) continue;
      if (pick < o.weight) { chosen = o.heading; break; }
      pick -= o.weight;
    }
    turn_to(chosen);
    heading_ = chosen;
    const int d = heading_ < 2 ? +1 : -1;
    if (horizontal()) line_ = row, target_ = col + d;
    else line_ = col, target_ = row + d;
  }

  void turn_to(int new_heading) {
    const double delta = shortest_turn(yaw_, heading_yaw(new_heading));
    const double start = yaw_;
    const int n = static_cast<int>(std::lround(p_.turn_frames * std::abs(delta) / (kPi / 2)));
    for (int k = 1; k <= n && !done(); ++k) {
      yaw_ = start + delta * smoothstep(static_cast<double>(k) / n);
      emit();
    }
    yaw_ = heading_yaw(new_heading);
  }

  const ManhattanLayout& layout_;
  const StreetWalkParams& p_;
  Random& rng_;
  const double step_;
  const double max_offset_;
  Camera base_;
  std::vector<Camera> frames_;
  Vec2 pos_;
  double yaw_ = 0.0;   // unwrapped; frames store it wrapped into [0, 2*pi)
  int heading_ = 0;
  int line_ = 0;       // index of the street walked (a y line when horizontal, else an x line)
  int target_ = 0;     // index of the next crossing line ahead
  double sway_phase_ = 0.0;
};

}  // namespace

void validate(const StreetWalkParams& p) {
  const ParamChecks check("path", "street_walk");
  check.in_range("frames", p.frames, 1, 1'000'000);
  check.above("frames_per_second", p.frames_per_second, 0.0, 1000.0);
  check.above("walking_speed", p.walking_speed, 0.0, 100.0);
  check.above("eye_height", p.eye_height, 0.0, 1.0e4);
  if (p.hfov_deg != 360.0 && !(p.hfov_deg > 0.0 && p.hfov_deg < 180.0))
    check.fail("hfov_deg", "must lie in (0, 180) or be 360 (omnidirectional) (got " + ParamChecks::text(p.hfov_deg) + ")");
  if (!(p.vfov_deg > 0.0 && p.vfov_deg < 180.0)) check.fail("vfov_deg", "must lie in (0, 180)");
  check.in_range("street_margin", p.street_margin, 0.0, 1000.0);
  check.in_range("sway", p.sway, 0.0, 0.5);
  check.in_range("turn_frames", p.turn_frames, 1, 100000);
  check.in_range("forward_weight", p.forward_weight, 0.0, 1.0e6);
  check.in_range("backward_weight", p.backward_weight, 0.0, 1.0e6);
  check.in_range("sidestep_weight", p.sidestep_weight, 0.0, 1.0e6);
  check.in_range("stop_weight", p.stop_weight, 0.0, 1.0e6);
  if (p.forward_weight <= 0.0) check.fail("forward_weight", "must be > 0 (the walk has to get somewhere)");
}

CameraPath street_walk(const ManhattanParams& city, const StreetWalkParams& walk, std::uint64_t seed) {
  validate(city);
  validate(walk);
  const ManhattanLayout layout = manhattan_layout(city);
  const double step = walk.walking_speed / walk.frames_per_second;
  const double max_offset = layout.street_width() / 2 - walk.street_margin;
  const ParamChecks check("path", "street_walk");
  if (max_offset < 0.0)
    check.fail("street_margin", "leaves no room in streets " + ParamChecks::text(layout.street_width()) + " m wide");
  if (step > max_offset + layout.street_width() / 2)
    check.fail("walking_speed", "one frame's step (" + ParamChecks::text(step) +
                                    " m) could carry the eye out of the street at an intersection");
  Random rng = Random::stream(seed, kWalkStream);
  Walker walker(layout, walk, rng);
  CameraPath path;
  path.kind = "street_walk";
  path.seed = seed;
  path.frames_per_second = walk.frames_per_second;
  path.frames = walker.run();
  return path;
}

CameraPath street_walk(const Scene& scene, const StreetWalkParams& walk, std::uint64_t seed) {
  const std::optional<ManhattanParams> city = manhattan_params_of(scene);
  if (!city) return free_space_walk(scene, walk, seed);
  return street_walk(*city, walk, seed);
}

}  // namespace cullcheck::generators
