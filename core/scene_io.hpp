// Scene, camera and path (de)serialisation as JSON (mesh formats, glTF and OBJ: core/formats/).
//
// Scene JSON (format "cullcheck-scene", version 1):
//   {"format": "cullcheck-scene", "version": 1,
//    "provenance": {"generator": "...", "seed": N, "parameters": {...}},
//    "origin": [x, y],                      // optional, world offset of local coordinates
//    "buildings": [{"id": N, "height": h, "footprint": [[x, y], ...]}, ...],
//    "meshes": [{"id": N, "name": "...", "vertices": [[x, y, z], ...],   // version 2 only
//                "triangles": [[i, j, k], ...]}, ...]}
// Footprints are implicitly closed (a repeated closing vertex is dropped); clockwise rings are
// reversed to counter-clockwise. Ids are unique across buildings and meshes. Version 1 holds
// buildings only; a scene with mesh objects is written as version 2 (so a reader that knows only
// version 1 refuses it instead of silently dropping its meshes). Anything else wrong raises
// InputError naming the object and field. Writing is deterministic: the same scene gives
// byte-identical text.
//
// Camera JSON: {"position": [x, y, z], "yaw", "pitch", "roll", "hfov", "vfov", "near", "far",
//  "projection": "perspective" | "orthographic", "ortho_width", "ortho_height",
//  "resolution": [width, height], "aspect": width / height}, all but position optional.
// "aspect" (read only) derives the missing one of hfov/vfov (ortho_width/ortho_height); without
// it, a given resolution's width / height does (square pixels). Giving both fields and an
// aspect is an error.
//
// Camera and path files may say which frame their positions are in (core/coordinates.hpp):
// "coordinates": "local" (scene-local metres, what files that do not say are read as) or "world"
// (local + the scene's origin), and with local ones "origin": [x, y], the origin they are local
// to. A path says it once, at its top level; a path frame that says it is an error, and so is a
// camera read where only scene-local cameras belong (camera_from_json_text).
#pragma once

#include <iosfwd>
#include <string>

#include "core/camera_path.hpp"
#include "core/scene.hpp"

namespace cullcheck {

// Limits that make absurd input an error rather than an out-of-memory crash.
inline constexpr std::size_t kMaxBuildings = 20'000'000;
inline constexpr std::size_t kMaxFootprintVertices = 4096;
inline constexpr double kMaxCoordinate = 1.0e9;   // metres, before rebasing
inline constexpr double kMaxHeight = 1.0e4;       // metres
inline constexpr std::size_t kMaxMeshVertices = 50'000'000;  // per mesh object
inline constexpr std::size_t kMaxMeshes = 20'000'000;
// Scenes whose bounding box lies farther than this from the origin are rebased on load.
inline constexpr double kRebaseThreshold = 1.0e5;

Scene scene_from_json_text(const std::string& text);
Scene read_scene_file(const std::string& path);
std::string scene_to_json_text(const Scene& scene);
void write_scene_file(const Scene& scene, const std::string& path);

// Validates and normalises one building in place (orientation, closing vertex), then fills its
// prisms and bounds. Used by the reader and by generators, so both obey the same rules.
void validate_and_finish(Building& b);
// Validates one mesh object (finite coordinates within the limits, indices in range, at least one
// triangle) and fills its bounds. Triangles of zero area (in double precision) are an error, or,
// with `drop_degenerate`, removed and counted (importers of glTF and OBJ, whose files often hold
// them: they cannot be seen, so dropping them changes no visible set).
std::size_t validate_and_finish(MeshObject& m, bool drop_degenerate = false);
// A validated building whose footprint is the axis-aligned rectangle [x0, x1] x [y0, y1].
Building box_building(ObjectId id, double x0, double y0, double x1, double y1, double height);
// A validated building on a counter-clockwise footprint (InputError when it is not simple).
Building footprint_building(ObjectId id, std::vector<Vec2> footprint, double height);
// Moves every coordinate so the scene's centre sits near (0, 0) when it is far from the origin.
void rebase_if_far(Scene& scene);

std::string camera_to_json_text(const Camera& camera);
// A scene-local camera (protocol frames, generator parameters): "coordinates"/"origin" are refused.
Camera camera_from_json_text(const std::string& text, const std::string& object = "camera");
// A camera as a user gives it (--camera, --from): a one-frame path with its frame, if it says one.
CameraPath single_camera_from_json_text(const std::string& text, const std::string& object = "camera");
std::string path_to_json_text(const CameraPath& path);
CameraPath path_from_json_text(const std::string& text);
// path_from_json_text of a file; errors name the file.
CameraPath read_path_file(const std::string& path);

// Whole-file helpers that raise InputError naming the file when it cannot be read or written;
// writes go to a temporary file that is renamed, so a failure never truncates existing output.
std::string read_text_file(const std::string& path);
void write_text_file_atomically(const std::string& path, const std::string& text);

}  // namespace cullcheck
