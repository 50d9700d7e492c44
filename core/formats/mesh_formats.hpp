// Mesh scene files in and out: glTF 2.0 (.glb, .gltf) and Wavefront OBJ (design: "A user's
// culling system is a subject: cullcheck hands it the scene (glTF/OBJ and scene JSON)").
//
// One object of a scene (a building or a mesh object) is one glTF node / one OBJ group, named
// `building_<id>` or `mesh_<id>`. Coordinates are always scene-local metres (Scene::origin is
// written beside them, never added to them: float32 vertices far from the origin would lose
// their millimetres).
//
//   write_glb            one node per object under a root node `cullcheck_scene` whose matrix
//                        turns cullcheck's z up into glTF's +Y up; node extras {"cullcheck_id",
//                        "kind"} and, for a building, its "footprint" and "height", so that a
//                        re-import recovers the very same prism (for a mesh object its "name");
//                        asset extras "cullcheck" hold the world origin and the provenance.
//                        Byte-deterministic. (gltf_writer.cpp)
//   write_obj            Assimp's OBJ exporter ("objnomtl"): one `g building_<id>` group per
//                        object, z up, scene-local; a header comment gives the world origin.
//                        (obj_writer.cpp)
//   read_gltf            .glb or .gltf (by content): the default scene (or every root node), node
//                        transforms composed in double precision, glTF's y up turned into z up.
//                        (gltf_reader.cpp)
//   read_obj             every `o`/`g` group an object, polygons triangulated by tinyobjloader
//                        (double precision), y or z up. (obj_reader.cpp)
//   read_scene_file_any  by extension: .json (core's reader), .glb/.gltf, .obj. (scene_file_any.cpp)
//   exported_meshes      the triangles every object is exported as. (exported_meshes.cpp)
//   as_vertical_prism    prism detection: a mesh that is a building. (vertical_prism.cpp)
//
// Every importer applies the same rules (import_objects.cpp):
//  - Ids: the source's extras "cullcheck_id" if present; else a name `building_<n>`, `mesh_<n>`,
//    `object_<n>` or all digits gives n; else the next free id after the largest taken, in file
//    order (node, mesh or group index). Two objects with one id are an InputError naming both.
//    The source is the node (IdSource::node; its name, or its mesh's when it has none) or the
//    glTF mesh (IdSource::mesh), or the OBJ group; its name is kept in MeshObject::name.
//  - Triangles of zero area are dropped and counted (validate_and_finish(m, true)).
//  - With detect_prisms, a mesh that is a vertical prism becomes a Building (so 2.5D methods run
//    on imported cities); extras footprint/height, when present and consistent with the mesh
//    (every vertex on the prism's outline at z = 0 or h, the same bounds), are used as given;
//    extras "kind": "mesh" (our writer's word that it was a mesh object) keeps a mesh a mesh;
//    the rest stay MeshObjects.
//  - Far-from-origin scenes are rebased (rebase_if_far) before prisms are detected.
// Malformed files raise InputError naming the file, the node or mesh and the field.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/formats/import_options.hpp"
#include "core/scene.hpp"

namespace cullcheck::formats {

// Limits beside core's kMax* (core/scene_io.hpp): absurd files are errors, not out-of-memory.
inline constexpr std::size_t kMaxSceneFileBytes = 0xFFFFFFFF;  // 4 GiB - 1 (.glb's own limit; tinygltf's too)
inline constexpr std::size_t kMaxTrianglesPerObject = 100'000'000;
inline constexpr std::size_t kMaxNodes = 50'000'000;

Scene read_gltf(const std::string& path, const ImportOptions& options = {}, ImportReport* report = nullptr);
Scene read_obj(const std::string& path, const ImportOptions& options = {}, ImportReport* report = nullptr);
// The name an object's glTF node / OBJ group is written with (a subject maps nodes to ids by it).
inline std::string building_node_name(ObjectId id) { return "building_" + std::to_string(id); }
inline std::string mesh_node_name(ObjectId id) { return "mesh_" + std::to_string(id); }

// By extension (case-insensitive): .json (cullcheck's scene JSON, or GeoJSON when the file says
// "FeatureCollection" or "Feature" near its start), .geojson, .glb, .gltf, .obj; anything else is
// an InputError.
Scene read_scene_file_any(const std::string& path, const ImportOptions& options = {}, ImportReport* report = nullptr);

// Both write a temporary file and rename it: a failure never truncates an existing output.
void write_glb(const Scene& scene, const std::string& path);
void write_obj(const Scene& scene, const std::string& path);
// The .glb bytes write_glb writes (for tests and for callers that stream).
std::string glb_bytes(const Scene& scene);

// The triangles of every object exactly as exported, buildings first, then meshes, in scene
// order: a building is its bottom and top rings (vertex 2i at z = 0 and 2i + 1 at its height,
// for footprint vertex i), two triangles per wall, its roof as a fan over each convex prism
// (zero-area fan triangles left out), no floor; a mesh object is itself.
std::vector<MeshObject> exported_meshes(const Scene& scene);
MeshObject exported_mesh(const Building& building);

// The building a mesh stands for when it is a vertical prism standing on z = 0: every vertex at
// z = 0 or at one height h > 0, every triangle horizontal or vertical, the top triangles' outline
// one simple polygon they cover exactly once, the walls covering that outline's vertical sides
// exactly (a floor, if any, covering the same outline). nullopt otherwise.
//
// Sound, not complete: it says yes only for meshes that bound the prism it returns, and may say
// no to some that do (T-junctions in a roof, vertices off a wall's straight line by more than the
// tolerance). Tolerance: kPrismTolerance times max(1 m, the mesh's largest |coordinate|), which
// covers float32 rounding (6e-8 relative) 16 times over; collinear outline vertices within it
// are merged. Vertices are welded by exact position, so a triangle soup is recognised.
inline constexpr double kPrismTolerance = 1e-6;
std::optional<Building> as_vertical_prism(const MeshObject& mesh);

}  // namespace cullcheck::formats
