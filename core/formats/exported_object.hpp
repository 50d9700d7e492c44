// The geometry and names objects are exported with (internal to cullcheck_formats; the public
// form is exported_meshes in mesh_formats.hpp).
#pragma once

#include <string>

#include "core/formats/mesh_formats.hpp"
#include "core/scene.hpp"

namespace cullcheck::formats::detail {

// A building's exported triangles (mesh_formats.hpp: exported_meshes), without bounds and
// `closed` (finish_mesh), which a writer does not need.
MeshObject building_surface(const Building& b);

inline std::string building_name(ObjectId id) { return building_node_name(id); }
inline std::string mesh_name(ObjectId id) { return mesh_node_name(id); }

}  // namespace cullcheck::formats::detail
