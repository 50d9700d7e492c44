// Seeded camera paths (design: "generators/"): a pedestrian street walk and a 6-DoF
// fly-through. Like the cities, a path is a pure function of its parameters and seed.
//
// Street walk: the thesis's walkthrough setting (ch. 4.4): a pedestrian at 5 km/h = 1.4 m/s,
// 30 frames per second (so 1.4 / 30 = 0.0467 m per walking frame), eye 1.7 m above the ground,
// walking the centre lines of a Manhattan grid's streets. Segments: forward (with a small
// sideways sway), backward, sideways steps (lateral movement: the case where an unguarded ΔH
// misses a thin building, thesis Fig. 3.10), stops with a look around, and turns at
// intersections where the yaw changes smoothly over several frames (turns between east and
// south cross the azimuth wrap at 0 / 2π). Every frame either stands still or moves exactly
// one step in the plan view. The eye never leaves the street strips, so it is never inside a
// building, and never within `street_margin` of a block.
//
// Fly-through: 6 DoF over any scene: cruising above the rooftops (highest roof + margin), with
// dips to street level at open points, pitch down to -80 degrees and roll, all smooth. The
// altitude is raised wherever needed to keep `clearance` from every wall and roof, so the eye
// is never inside a building.
#pragma once

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "core/camera_path.hpp"
#include "core/scene.hpp"
#include "generators/city.hpp"

namespace cullcheck::generators {

struct StreetWalkParams {
  int frames = 1800;
  double frames_per_second = 30.0;
  double walking_speed = 1.4;        // m/s
  double eye_height = 1.7;           // m
  double hfov_deg = 60.0;            // 360 = omnidirectional
  double vfov_deg = 45.0;
  double street_margin = 1.0;        // least distance kept from the blocks on either side, m
  double sway = 0.15;                // peak sideways share of a forward step
  int turn_frames = 20;              // frames for a 90-degree turn (a U-turn takes twice as many)
  double forward_weight = 0.55;      // relative weights of the segment kinds
  double backward_weight = 0.12;
  double sidestep_weight = 0.18;
  double stop_weight = 0.15;

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("frames", s.frames), v("frames_per_second", s.frames_per_second), v("walking_speed", s.walking_speed);
    v("eye_height", s.eye_height), v("hfov_deg", s.hfov_deg), v("vfov_deg", s.vfov_deg);
    v("street_margin", s.street_margin), v("sway", s.sway), v("turn_frames", s.turn_frames);
    v("forward_weight", s.forward_weight), v("backward_weight", s.backward_weight);
    v("sidestep_weight", s.sidestep_weight), v("stop_weight", s.stop_weight);
  }
};

struct FlyThroughParams {
  int frames = 900;
  double frames_per_second = 30.0;
  double cruise_speed = 12.0;        // m/s at cruise altitude
  double street_speed = 3.0;         // m/s at street level
  double rooftop_margin = 15.0;      // cruise altitude above the highest roof, m
  double street_eye_height = 2.0;    // altitude of a dip, m
  double dip_fraction = 0.3;         // share of waypoints at street level
  double clearance = 0.5;            // least distance kept from every wall and roof, m
  double min_pitch_deg = -80.0;
  double max_pitch_deg = 30.0;
  double max_roll_deg = 25.0;
  double max_turn_rate_deg = 90.0;   // per second: the view follows the path's bends this fast
  double hfov_deg = 60.0;            // 360 = omnidirectional
  double vfov_deg = 45.0;

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("frames", s.frames), v("frames_per_second", s.frames_per_second), v("cruise_speed", s.cruise_speed);
    v("street_speed", s.street_speed), v("rooftop_margin", s.rooftop_margin);
    v("street_eye_height", s.street_eye_height), v("dip_fraction", s.dip_fraction), v("clearance", s.clearance);
    v("min_pitch_deg", s.min_pitch_deg), v("max_pitch_deg", s.max_pitch_deg), v("max_roll_deg", s.max_roll_deg);
    v("max_turn_rate_deg", s.max_turn_rate_deg);
    v("hfov_deg", s.hfov_deg), v("vfov_deg", s.vfov_deg);
  }
};

// The thesis's Table 4.1 walk (plaza_crossing.cpp): along a street to a plaza, across it
// diagonally, then up the street leaving its far corner. Lengths in metres.
struct PlazaCrossingParams {
  double step_m = 2.0;             // one frame per step
  double turn_step_deg = 7.0;      // turns are split into steps no larger than this
  double first_street_m = 566.0;   // the thesis's first street
  double second_street_m = 550.0;
  double eye_height = 1.7;
  double hfov_deg = 60.0;
  double vfov_deg = 45.0;

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("step_m", s.step_m), v("turn_step_deg", s.turn_step_deg), v("first_street_m", s.first_street_m);
    v("second_street_m", s.second_street_m);
    v("eye_height", s.eye_height), v("hfov_deg", s.hfov_deg), v("vfov_deg", s.vfov_deg);
  }
};

// InputError(object "path", field = parameter name) for unusable values.
void validate(const StreetWalkParams& p);
void validate(const FlyThroughParams& p);
void validate(const PlazaCrossingParams& p);

// Walks the streets of the Manhattan grid that manhattan_city(city, ...) builds (any seed:
// streets do not depend on the city's seed).
CameraPath street_walk(const ManhattanParams& city, const StreetWalkParams& walk, std::uint64_t seed);
// The same for a scene made by manhattan, plaza, default, thesis, openings or detailed (streets read from its
// provenance); any other scene (irregular, scatter, an imported city) gets free_space_walk.
CameraPath street_walk(const Scene& scene, const StreetWalkParams& walk, std::uint64_t seed);
// A pedestrian walk through the free-space cells of any scene (free_space_walk.cpp): the same
// segments (forward, backward, sideways, stops) along a random route from cell centre to shared
// edge to cell centre, street_margin clear of every wall. InputError when no cell is walkable.
CameraPath free_space_walk(const Scene& scene, const StreetWalkParams& walk, std::uint64_t seed);
CameraPath fly_through(const Scene& scene, const FlyThroughParams& fly, std::uint64_t seed);
// InputError unless the scene has a plaza (plaza or default generator).
CameraPath plaza_crossing(const Scene& scene, const PlazaCrossingParams& walk);

// Dispatch by kind (camera_path_kinds()); `params` overlays the kind's defaults. Any kind also
// takes "timeline": {"every", "churn", "late"} (scene_timeline_gen.hpp), a seeded scene timeline.
const std::vector<std::string>& camera_path_kinds();
CameraPath make_camera_path(const std::string& kind, const Scene& scene, std::uint64_t seed, const nlohmann::json& params);

}  // namespace cullcheck::generators
