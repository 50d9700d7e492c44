// What the glTF and OBJ readers share (internal to cullcheck_formats): the id rules, validation,
// degenerate dropping, rebasing and prism detection of mesh_formats.hpp, applied in one place so
// both formats obey them alike.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/formats/mesh_formats.hpp"

namespace cullcheck::formats::detail {

// Extras our own writer gives an object: "cullcheck_id", "kind", for a building "footprint" and
// "height" (scene-local, z up), for a named mesh object its "name".
struct GivenExtras {
  std::optional<std::uint64_t> id;
  bool kind_mesh = false;             // "kind": "mesh": the writer says it was a mesh object
  std::optional<std::string> name;    // "name": a mesh object's own name (MeshObject::name)
  std::optional<Building> prism;      // not yet validated
};

// One object as a reader found it, in cullcheck's frame (z up) and the file's coordinates.
struct ImportedObject {
  std::string source;   // for messages: e.g. "node 4 'building_7'"
  std::string name;     // kept in MeshObject::name
  GivenExtras given;
  MeshObject mesh;      // vertices and triangles (not yet validated)
};

// The id a name carries: `building_<n>`, `mesh_<n>`, `object_<n>` or all digits; nullopt when
// it carries none. Throws InputError(object, "name") when n does not fit an id.
std::optional<ObjectId> id_from_name(const std::string& name, const std::string& object);

// Reads GivenExtras from an object's extras JSON text (tinygltf keeps it verbatim, so ids and
// coordinates are exact). Unknown keys are ignored; known keys of the wrong shape are an
// InputError(object, "extras.<key>").
GivenExtras parse_given_extras(const std::string& extras_json, const std::string& object);

// Ids (given, then from names, then the next free ones in file order), validation, rebasing,
// prisms. Every error is located at `file`. `scene` brings provenance and origin.
Scene finish_import(std::vector<ImportedObject> objects, Scene scene, const ImportOptions& options,
                    ImportReport* report, const std::string& file);

}  // namespace cullcheck::formats::detail
