// Closed meshes for the openings city (openings_geometry.hpp).
#include "generators/openings_geometry.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace cullcheck::generators {
namespace {

// A mesh corner in local (u, v, z) millimetres.
struct Corner {
  Millimetres u, v, z;
};

// Builds a mesh in local (u, v, z) millimetres, placing vertices once each.
class LocalMesh {
 public:
  explicit LocalMesh(const PlanFrame& frame) : frame_(frame) {}

  std::uint32_t vertex(Millimetres u, Millimetres v, Millimetres z) {
    auto [it, added] = index_.emplace(std::tuple{u, v, z}, static_cast<std::uint32_t>(mesh_.vertices.size()));
    if (added) {
      mesh_.vertices.push_back(frame_.place(u, v, z));
      local_.push_back({static_cast<double>(u), static_cast<double>(v), static_cast<double>(z)});
    }
    return it->second;
  }

  // A planar quad a-b-c-d (in order around it), as two triangles facing `outward` (local axes).
  // New corners are numbered d first, then c, b, a: vertex numbering is part of the scene that the
  // pinned digests fix (generators/tests/pinned_streams_test.cpp), and this is the order the
  // numbering had when the corners were placed inside the call's arguments, whose order of
  // evaluation C++ leaves open (gcc went right to left, clang left to right).
  void quad(Corner ca, Corner cb, Corner cc, Corner cd, Vec3 outward) {
    const std::uint32_t d = vertex(cd.u, cd.v, cd.z), c = vertex(cc.u, cc.v, cc.z), b = vertex(cb.u, cb.v, cb.z),
                        a = vertex(ca.u, ca.v, ca.z);
    const Vec3 n = cross(local_[b] - local_[a], local_[c] - local_[a]);
    if (dot(n, outward) > 0) {
      mesh_.triangles.push_back({a, b, c});
      mesh_.triangles.push_back({a, c, d});
    } else {
      mesh_.triangles.push_back({a, c, b});
      mesh_.triangles.push_back({a, d, c});
    }
  }

  MeshObject take() { return std::move(mesh_); }

 private:
  PlanFrame frame_;
  MeshObject mesh_;
  std::vector<Vec3> local_;
  std::map<std::tuple<Millimetres, Millimetres, Millimetres>, std::uint32_t> index_;
};

}  // namespace

MeshObject facade_wall_mesh(const PlanFrame& frame, Millimetres start, Millimetres length, Millimetres thickness,
                            Millimetres height, const std::vector<Opening>& openings) {
  std::vector<Millimetres> us{0, length}, zs{0, height};
  for (const Opening& o : openings) us.push_back(o.u0), us.push_back(o.u1), zs.push_back(o.z0), zs.push_back(o.z1);
  std::sort(us.begin(), us.end());
  us.erase(std::unique(us.begin(), us.end()), us.end());
  std::sort(zs.begin(), zs.end());
  zs.erase(std::unique(zs.begin(), zs.end()), zs.end());
  const int nu = static_cast<int>(us.size()) - 1, nz = static_cast<int>(zs.size()) - 1;
  // Cell (a, b) = [us[a], us[a+1]] x [zs[b], zs[b+1]]; outside the face counts as empty.
  auto filled = [&](int a, int b) {
    if (a < 0 || b < 0 || a >= nu || b >= nz) return false;
    return std::none_of(openings.begin(), openings.end(), [&](const Opening& o) {
      return o.u0 <= us[a] && us[a + 1] <= o.u1 && o.z0 <= zs[b] && zs[b + 1] <= o.z1;
    });
  };
  LocalMesh m(frame);
  auto at = [&](int a, int b, Millimetres v) { return Corner{start + us[a], v, zs[b]}; };
  for (int a = 0; a < nu; ++a)
    for (int b = 0; b < nz; ++b) {
      if (!filled(a, b)) continue;
      m.quad(at(a, b, 0), at(a + 1, b, 0), at(a + 1, b + 1, 0), at(a, b + 1, 0), {0, -1, 0});  // street side
      m.quad(at(a, b, thickness), at(a + 1, b, thickness), at(a + 1, b + 1, thickness), at(a, b + 1, thickness),
             {0, 1, 0});
    }
  // Reveals and outer sides: one quad per grid segment with a filled cell on one side only.
  for (int a = 0; a <= nu; ++a)
    for (int b = 0; b < nz; ++b) {
      const bool left = filled(a - 1, b), right = filled(a, b);
      if (left == right) continue;
      m.quad(at(a, b, 0), at(a, b + 1, 0), at(a, b + 1, thickness), at(a, b, thickness), {left ? 1.0 : -1.0, 0, 0});
    }
  for (int b = 0; b <= nz; ++b)
    for (int a = 0; a < nu; ++a) {
      const bool below = filled(a, b - 1), above = filled(a, b);
      if (below == above) continue;
      m.quad(at(a, b, 0), at(a + 1, b, 0), at(a + 1, b, thickness), at(a, b, thickness), {0, 0, below ? 1.0 : -1.0});
    }
  return m.take();
}

MeshObject box_mesh(const PlanFrame& frame, Millimetres u0, Millimetres v0, Millimetres z0, Millimetres u1,
                    Millimetres v1, Millimetres z1) {
  LocalMesh m(frame);
  auto p = [&](int i, int j, int k) { return Corner{i ? u1 : u0, j ? v1 : v0, k ? z1 : z0}; };
  m.quad(p(0, 0, 0), p(1, 0, 0), p(1, 1, 0), p(0, 1, 0), {0, 0, -1});
  m.quad(p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1), {0, 0, 1});
  m.quad(p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1), {0, -1, 0});
  m.quad(p(0, 1, 0), p(1, 1, 0), p(1, 1, 1), p(0, 1, 1), {0, 1, 0});
  m.quad(p(0, 0, 0), p(0, 1, 0), p(0, 1, 1), p(0, 0, 1), {-1, 0, 0});
  m.quad(p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1), {1, 0, 0});
  return m.take();
}

void append_part(MeshObject& into, const MeshObject& part) {
  const auto base = static_cast<std::uint32_t>(into.vertices.size());
  into.vertices.insert(into.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (const auto& t : part.triangles) into.triangles.push_back({base + t[0], base + t[1], base + t[2]});
}

}  // namespace cullcheck::generators
