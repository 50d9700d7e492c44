// World and scene-local coordinates of cameras (design: "Scene model", "Numerical extremes").
//
// Scenes far from the origin are rebased on load: vertices are scene-local and Scene::origin
// says where local (0, 0) lies in the world (world = local + origin; z is never moved). A camera
// or path file says which frame its positions are in ("coordinates": "local" or "world", and
// with local ones optionally the "origin" they are local to; core/scene_io.hpp). A file that
// does not say is read as local: that is what cullcheck has always written (generate
// --path-output) and read, so old files keep their meaning. A command-line default
// (--coordinates world|local) applies to files that do not say; one that contradicts a file is
// an error.
//
// A camera in the wrong frame sees nothing, and a culler that culls everything passes the
// conservative check there: so a path (or camera) whose every eye lies outside the scene's plan
// bounds grown by eye_margin() is refused as bad input, naming the file, the first eye, the
// bounds and the origin.
#pragma once

#include <optional>
#include <string>

#include "core/camera_path.hpp"
#include "core/scene.hpp"

namespace cullcheck {

const char* frame_name(CoordinateFrame frame);  // "local", "world"
// "local" or "world", else an InputError naming `flag`.
CoordinateFrame parse_coordinate_frame(const std::string& text, const std::string& flag = "--coordinates");

// What a path's positions were given in, how that was decided, and what became of them.
struct CoordinateConversion {
  CoordinateFrame given = CoordinateFrame::local;
  std::string decided_by = "default";  // "file" (its "coordinates"/"origin"), "--coordinates" or "default"
  Vec2 origin;                         // the scene's: world = local + origin
  std::optional<Vec2> declared_origin;  // a local file's own "origin"
  bool moved = false;                   // some position changed (world given, or another origin)
  double rounding_m = 0.0;              // largest rounding of a local position moved to the origin
};

// Turns `path` into scene-local coordinates of `scene`: world positions minus the origin, local
// ones relative to another declared origin moved to the scene's. World positions convert exactly
// (checked: with a whole-metre origin, as rebasing makes it, they do for every eye nearer the
// origin than world (0, 0)); one that would round is an InputError naming `file` and the frame.
// A local position moved to another origin is rounded once, by less than half an ulp of the
// result (finer than any world position there), and the largest rounding is kept.
// `fallback` is the frame of a file that does not say (--coordinates; nullopt: local); a fallback
// that contradicts the file is an InputError. Afterwards the path says local, with the origin.
CoordinateConversion to_scene_local(CameraPath& path, const Scene& scene, std::optional<CoordinateFrame> fallback,
                                    const std::string& file);

// How far (plan metres) beyond the scene's bounds an eye may lie: max(1 km, the bounds' larger
// side). A world position read as local on a rebased scene lies at least ~1e5 m off (rebasing
// starts at kRebaseThreshold), a legitimate overview rarely farther than the city is wide.
double eye_margin(const Scene& scene);
// An InputError naming `file`, the first eye, the bounds and the origin when every eye of `path`
// (scene-local) lies outside the scene's plan bounds grown by eye_margin. Height is not checked
// (the origin never moves z). No check on a scene without objects.
void require_an_eye_near_the_scene(const CameraPath& path, const Scene& scene, const CoordinateConversion& how,
                                   const std::string& file);

// One line for the printed summaries and the gate, e.g. "coordinates: scene-local metres, world =
// local + origin [5000000, 3000000]; walk.json was given in world coordinates (said by the
// file), converted to local".
std::string coordinates_line(const CoordinateConversion& c, const std::string& file);

}  // namespace cullcheck
