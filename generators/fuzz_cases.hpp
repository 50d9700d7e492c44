// RapidCheck generators of the cases `cullcheck fuzz` sends to an outside culling system
// (README "Fuzzing an outside program"): a small seeded scene (generators/rapidcheck_gens.hpp's
// cities, and mesh scenes with openings) and a short camera path of one of the kinds real
// cullers get wrong. Every case prints as the flags that rebuild it, and shrinks towards a
// smaller scene and fewer, simpler frames.
//
// Path kinds:
//   viewport_edge  a corner of one object's bounding box placed just inside a side, top or
//                  bottom edge of the view (0.01-2 degrees in): bounding-volume bugs
//   lateral        sideways steps of 5 cm to 3 m past the scene's objects: thin walls, and
//                  temporal cullers that reuse the last frame
//   tilted         pitched (up to ±90 degrees) and rolled cameras, street level or above roofs
//   orthographic   orthographic cameras, top-down or oblique (only for subjects that take them)
//   near_plane     an eye 2 cm to 1 m in front of an object's face, near planes 1 cm to 0.5 m
//   street         the properties' street and rooftop cameras (ordinary, narrow, 360 degrees)
//
// Link target: cullcheck_generators_rc (bodies in fuzz_cases.cpp).
#pragma once

#include <rapidcheck.h>

#include <cmath>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "core/camera_path.hpp"
#include "core/scene_io.hpp"
#include "generators/angles.hpp"
#include "generators/rapidcheck_gens.hpp"

namespace cullcheck::generators {

struct FuzzCase {
  SceneSpec spec;
  std::string kind;  // one of the path kinds above
  CameraPath path;
};

inline std::ostream& operator<<(std::ostream& os, const FuzzCase& c) {
  os << replay_args(c.spec) << " (" << c.kind << ", " << c.path.frames.size() << " frames)";
  for (const Camera& cam : c.path.frames) {
    os << "\n  ";
    showValue(cam, os);
  }
  return os;
}
inline void showValue(const FuzzCase& c, std::ostream& os) { os << c; }

namespace rcgen {

// Mesh scenes with openings (generators/openings_city.cpp): 1-2 x 1-2 blocks of 1-4 core lots,
// facades with doors and windows, arcades and bridges by weight (each may shrink to none).
rc::Gen<SceneSpec> openings_spec();

// The fuzzer's scenes: the properties' small cities and mesh scenes with openings.
rc::Gen<SceneSpec> fuzz_scene_spec();

// A street or rooftop eye aimed so that one corner of one object's box lies just inside an edge
// of the view: side edges turn the yaw, top and bottom edges the pitch.
rc::Gen<CameraPath> viewport_edge_path(const Scene& scene);

// A street camera stepping sideways 1-6 times by 5 cm to 3 m, sometimes turning a little.
rc::Gen<CameraPath> lateral_path(const Scene& scene);

// Pitched and rolled: the rooftop generator's full range, or a street eye looking up.
rc::Gen<CameraPath> tilted_path(const Scene& scene);

// Orthographic: top-down over part of the scene, or oblique at street level.
rc::Gen<CameraPath> orthographic_path(const Scene& scene);

// An eye 2 cm to 1 m in front of the middle of an object's box side, looking at it or along it.
rc::Gen<CameraPath> near_plane_path(const Scene& scene);

rc::Gen<CameraPath> street_path(const Scene& scene);

// A scene and a path for it; `orthographic` when the subject takes orthographic cameras.
rc::Gen<FuzzCase> fuzz_case(rc::Gen<SceneSpec> specs, bool orthographic);

}  // namespace rcgen
}  // namespace cullcheck::generators
