// cullcheck's frame against glTF's (internal to cullcheck_formats).
//
// cullcheck is right-handed with z up; glTF is right-handed with +Y up (glTF 2.0 spec, 3.4:
// "glTF uses a right-handed coordinate system ... +Y is up"). The rotation by -90 degrees about
// x maps one onto the other: glTF (X, Y, Z) = (x, z, -y), and back x = X, y = -Z, z = Y. The
// writer puts it on its root node, the reader applies its inverse after composing every node's
// transform, so our own files re-import to the coordinates they were written from; both are
// exact (entries 0 and +-1).
#pragma once

#include <array>

#include "core/geometry.hpp"

namespace cullcheck::formats::detail {

// Column-major, as glTF's node.matrix: columns are the images of x, y, z and the translation.
inline constexpr std::array<double, 16> kZUpToYUp = {1, 0, 0, 0,   //
                                                     0, 0, -1, 0,  //
                                                     0, 1, 0, 0,   //
                                                     0, 0, 0, 1};

constexpr Vec3 y_up_to_z_up(Vec3 gltf) { return {gltf.x, -gltf.z, gltf.y}; }

inline constexpr const char* kRootNodeName = "cullcheck_scene";

}  // namespace cullcheck::formats::detail
