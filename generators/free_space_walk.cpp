// Pedestrian street walk on any scene (camera_paths.hpp: street_walk on a scene without a
// Manhattan grid, e.g. an imported city): a random route through the free-space cells of
// navigable_regions.hpp.
//
// The route goes from a cell's centre to the midpoint of the edge it shares with a neighbour,
// then to that neighbour's centre. Cells are convex and hold no building, so every point of
// those legs is in the open; a neighbour is taken only when its shared edge is at least
// 2 x street_margin long and the midpoint and its centre are street_margin clear of every wall.
// Segments as on the grid: forward along the route (each frame one step, cut short where it
// reaches a bend of the route, the view turning
// towards the way ahead at most 90 degrees per turn_frames), backward (retracing the frames
// walked), sideways steps (within the current cell, street_margin clear) and stops. The eye is
// at eye_height, never inside a building.
#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "generators/angles.hpp"
#include "generators/camera_paths.hpp"
#include "generators/navigable_regions.hpp"
#include "generators/open_space.hpp"
#include "generators/random.hpp"
#include "generators/walk_segments.hpp"

namespace cullcheck::generators {
namespace {

constexpr std::uint64_t kFreeWalkStream = 0x46574C4B;  // "FWLK"

Vec2 centre_of(const std::vector<Vec2>& ring) {
  Vec2 c{0, 0};
  for (Vec2 v : ring) c = c + v;
  return c * (1.0 / static_cast<double>(ring.size()));
}

class FreeWalker {
 public:
  FreeWalker(const std::vector<NavigableRegion>& cells, const OpenSpace& open, const StreetWalkParams& p, Random& rng)
      : cells_(cells), open_(open), p_(p), rng_(rng), step_(p.walking_speed / p.frames_per_second),
        max_turn_((kPi / 2) / std::max(1, p.turn_frames)) {
    base_.position.z = p.eye_height;
    base_.hfov = p.hfov_deg >= 360.0 ? kTwoPi : radians(p.hfov_deg);
    base_.vfov = radians(p.vfov_deg);
  }

  // False when no cell is a usable start (every centre too close to a wall, or no neighbour).
  bool start() {
    std::vector<std::uint32_t> usable;
    for (const NavigableRegion& c : cells_)
      if (open_.is_open(centre_of(c.ring), p_.street_margin) && !exits(c.id).empty()) usable.push_back(c.id);
    if (usable.empty()) return false;
    cell_ = usable[static_cast<std::size_t>(rng_.uniform_int(0, static_cast<std::int64_t>(usable.size()) - 1))];
    pos_ = centre_of(cells_[cell_].ring);
    if (!plan_next()) return false;
    yaw_ = azimuth_of(target_ - pos_);
    emit();
    return true;
  }

  std::vector<Camera> run() {
    while (!done()) {
      const WalkSegment s = next_walk_segment(p_, rng_, 3.0);
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
    trail_.push_back(pos_);
  }

  // Neighbours of `cell` a walker can pass to: (neighbour, shared edge's midpoint).
  std::vector<std::pair<std::uint32_t, Vec2>> exits(std::uint32_t cell) const {
    std::vector<std::pair<std::uint32_t, Vec2>> out;
    for (std::uint32_t n : cells_[cell].neighbours) {
      const auto edge = shared_edge(cells_[cell].ring, cells_[n].ring);
      if (!edge || length(edge->second - edge->first) < 2 * p_.street_margin) continue;
      const Vec2 mid = (edge->first + edge->second) * 0.5;
      if (!open_.is_open(mid, p_.street_margin) || !open_.is_open(centre_of(cells_[n].ring), p_.street_margin)) continue;
      out.push_back({n, mid});
    }
    return out;
  }

  // The next leg: to the midpoint of an exit (not straight back where there is a choice), then
  // to that neighbour's centre. False when the cell has no exit (the walker then stands).
  bool plan_next() {
    std::vector<std::pair<std::uint32_t, Vec2>> out = exits(cell_);
    if (out.size() > 1) std::erase_if(out, [&](const auto& e) { return e.first == previous_; });
    if (out.empty()) return false;
    const auto& pick = out[static_cast<std::size_t>(rng_.uniform_int(0, static_cast<std::int64_t>(out.size()) - 1))];
    next_cell_ = pick.first;
    target_ = pick.second;
    through_ = false;
    return true;
  }

  // Turns the view towards `want` by at most max_turn_; true when it is within that of it.
  bool turn_towards(double want) {
    const double d = std::remainder(want - yaw_, kTwoPi);
    if (std::abs(d) <= max_turn_) {
      yaw_ = want;
      return true;
    }
    yaw_ += d > 0 ? max_turn_ : -max_turn_;
    return false;
  }

  void forward(int frames) {
    for (int k = 0; k < frames && !done(); ++k) {
      const Vec2 to = target_ - pos_;
      const double left = length(to);
      if (left < 1e-9) {  // at the target: the next one, or stand where there is none
        bool moved_on = true;
        if (!through_) {
          previous_ = cell_;
          cell_ = next_cell_;
          target_ = centre_of(cells_[cell_].ring);
          through_ = true;
        } else {
          moved_on = plan_next();
        }
        if (!moved_on || length(target_ - pos_) < 1e-9) emit();  // no way on from here this frame
        continue;
      }
      // Turn first while the way ahead is more than a frame's turn off the view.
      if (!turn_towards(azimuth_of(to))) {
        emit();
        continue;
      }
      pos_ = left <= step_ ? target_ : pos_ + to * (step_ / left);
      emit();
    }
  }

  // Back along the frames walked, one step (or standstill) per frame, facing as before. The
  // route then resumes from the centre of the cell the walker stands in (a straight leg within
  // that convex cell).
  void backward(int frames) {
    bool moved = false;
    for (int k = 0; k < frames && !done() && trail_.size() >= 2; ++k) {
      trail_.pop_back();
      pos_ = trail_.back();
      trail_.pop_back();
      emit();
      moved = true;
    }
    if (!moved) return;
    const std::int64_t here = locate_region(cells_, pos_, 1e-9);
    if (here < 0) return;  // on no cell's closed ring cannot happen: every frame was on the route
    if (static_cast<std::uint32_t>(here) != cell_) previous_ = cell_;
    cell_ = static_cast<std::uint32_t>(here);
    target_ = centre_of(cells_[cell_].ring);
    through_ = true;
  }

  // Sideways (positive: to the left of the view), one step a frame, while the eye stays in the
  // current cell and street_margin clear of every wall; then the route resumes from there
  // (both legs of a route lie in convex cells, so the way back to it is open too).
  void sidestep(double metres) {
    const Vec2 dir{std::cos(yaw_ + kPi / 2), std::sin(yaw_ + kPi / 2)};
    const int steps = static_cast<int>(std::abs(metres) / step_);
    const Vec2 move = dir * (metres < 0 ? -step_ : step_);
    for (int k = 0; k < steps && !done(); ++k) {
      const Vec2 next = pos_ + move;
      if (!ring_contains(cells_[cell_].ring, next) || !open_.is_open(next, p_.street_margin)) break;
      pos_ = next;
      emit();
    }
  }

  // Standing, looking left and right (up to 45 degrees) and back.
  void stop(int frames) {
    const double facing = yaw_, side = rng_.bernoulli(0.5) ? 1.0 : -1.0;
    for (int k = 0; k < frames && !done(); ++k) {
      const double phase = static_cast<double>(k + 1) / frames;  // 0..1: out and back
      yaw_ = facing + side * (kPi / 4) * std::sin(kPi * phase);
      emit();
    }
    yaw_ = facing;
  }

  const std::vector<NavigableRegion>& cells_;
  const OpenSpace& open_;
  const StreetWalkParams& p_;
  Random& rng_;
  const double step_, max_turn_;
  Camera base_;
  std::vector<Camera> frames_;
  std::vector<Vec2> trail_;
  Vec2 pos_{0, 0}, target_{0, 0};
  double yaw_ = 0.0;
  std::uint32_t cell_ = 0, next_cell_ = 0, previous_ = 0;
  bool through_ = false;  // heading for the current cell's centre (else for an exit's midpoint)
};

}  // namespace

CameraPath free_space_walk(const Scene& scene, const StreetWalkParams& walk, std::uint64_t seed) {
  validate(walk);
  const std::vector<NavigableRegion> cells = free_space_cells(scene);
  const OpenSpace open(scene);
  Random rng = Random::stream(seed, kFreeWalkStream);
  FreeWalker walker(cells, open, walk, rng);
  if (!walker.start())
    throw InputError("path", "kind", "street_walk finds no open ground in the scene to walk on (no free-space cell whose centre is " +
                                         std::to_string(walk.street_margin) + " m clear of every wall has a way on)");
  CameraPath path;
  path.kind = "street_walk";
  path.seed = seed;
  path.frames_per_second = walk.frames_per_second;
  path.frames = walker.run();
  return path;
}

}  // namespace cullcheck::generators
