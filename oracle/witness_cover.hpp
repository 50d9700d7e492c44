// Which triangles draw the point a witness ray sees.
//
// A ray that grazes an edge, or meets a vertex, touches every triangle around that point at the
// same distance, and Embree credits one of them, whichever its traversal meets first. On a closed
// solid that may be a face turned away from the eye: it is the face's edge that is seen, and the
// face beside it that turns toward the eye draws the same point. A method that drops a triangle
// the oracle credited has still drawn what the ray saw when another triangle of the same object
// that it keeps contains the hit point (within `tolerance_m`, for the single-precision hit) and
// faces the ray or stands edge-on to it (a face turned away is not drawn with back faces culled).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "oracle/mesh.hpp"
#include "oracle/ray_oracle.hpp"

namespace cullcheck::oracle {

// Whether the mesh's triangle turns its back to a ray of this direction (its normal, by the
// winding, points along the ray); edge-on is not turned away.
bool turned_away_from(const TriangleMesh& mesh, std::uint32_t triangle, Vec3 direction);

// Distance from p to the closed triangle abc (double precision).
double point_triangle_distance(Vec3 p, Vec3 a, Vec3 b, Vec3 c);

// Whether a triangle of object `object_index` (mesh.hpp: buildings, then meshes) that `drawn`
// keeps (by its index within the object) draws the point `ray` saw: it contains ray.hit_point
// within tolerance_m and does not turn its back to the ray.
bool seen_point_drawn(const TriangleMesh& mesh, std::uint32_t object_index, const WitnessRay& ray,
                      const std::function<bool(std::uint32_t local)>& drawn, double tolerance_m = 1e-3);

// How a method's kept triangles answer one witness (triangle `prim`, seen along `ray`): the object
// is culled (`kept` null), or `kept` holds the object's triangles it draws, by index within the
// object (a building, mesh.hpp's 2.5D prisms, is drawn whole when kept at all).
enum class WitnessVerdict : std::uint8_t {
  drawn,             // the credited triangle is kept
  drawn_by_another,  // dropped, but a kept face beside it draws the point (seen_point_drawn)
  missed,            // a violation
};
WitnessVerdict witness_verdict(const TriangleMesh& mesh, std::uint32_t prim, const WitnessRay& ray, const std::vector<char>* kept);

}  // namespace cullcheck::oracle
