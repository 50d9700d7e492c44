// Closed meshes for the openings city (city.hpp: "openings"), on the 1 mm grid.
//
// Shapes are built in a local frame (u along a street front, v inward from it, z up) and placed
// by a PlanFrame: a whole-millimetre origin and a quarter turn, so placing is exact and keeps
// handedness (u x v = z), and with it the outward winding of every face.
#pragma once

#include <vector>

#include "core/scene.hpp"
#include "generators/grid_snap.hpp"

namespace cullcheck::generators {

struct PlanFrame {
  Millimetres origin_x = 0, origin_y = 0;
  int u_x = 1, u_y = 0;  // the u axis in plan; v is u turned a quarter counter-clockwise
  Vec3 place(Millimetres u, Millimetres v, Millimetres z) const {
    return {metres(origin_x + u * u_x - v * u_y), metres(origin_y + u * u_y + v * u_x), metres(z)};
  }
};

// A rectangular opening in a wall's face: [u0, u1] along the wall (from its start) x [z0, z1].
struct Opening {
  Millimetres u0 = 0, z0 = 0, u1 = 0, z1 = 0;
};

// A wall slab [0, length] x [0, thickness] x [0, height] (local u, v, z; v = 0 faces the street)
// with rectangular openings through it: doors (z0 = 0, notches in its foot) and windows (holes).
// Openings must lie inside the face and not touch each other (a corner shared by two would make
// the surface non-manifold). The face is cut along every opening's lines into a grid; filled
// cells give the front and back faces, every grid segment between a filled and an empty cell a
// reveal quad through the thickness, so the mesh is closed with no T-junction, and it has one
// handle per window. Vertices in the frame, u offset by `start`. Not yet validated.
MeshObject facade_wall_mesh(const PlanFrame& frame, Millimetres start, Millimetres length, Millimetres thickness,
                            Millimetres height, const std::vector<Opening>& openings);

// A closed box [u0, u1] x [v0, v1] x [z0, z1] in the frame (12 triangles, faces outward).
MeshObject box_mesh(const PlanFrame& frame, Millimetres u0, Millimetres v0, Millimetres z0, Millimetres u1,
                    Millimetres v1, Millimetres z1);

// Appends `part`'s vertices and triangles to `into` (each part stays closed on its own).
void append_part(MeshObject& into, const MeshObject& part);

}  // namespace cullcheck::generators
