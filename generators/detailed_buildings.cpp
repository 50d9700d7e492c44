#include "generators/detailed_buildings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

#include "core/random.hpp"
#include "generators/grid_snap.hpp"
#include "generators/param_checks.hpp"
#include "generators/params_json.hpp"

namespace cullcheck::generators {
namespace {

constexpr Vec3 kUp{0.0, 0.0, 1.0};

// One closed solid of a mesh: its vertices welded by position (only within the solid, so two
// solids that touch never share an edge), each triangle turned to face `outward`.
class Solid {
 public:
  explicit Solid(MeshObject& mesh) : mesh_(mesh) {}
  void tri(Vec3 a, Vec3 b, Vec3 c, Vec3 outward) {
    if (dot(cross(b - a, c - a), outward) < 0) std::swap(b, c);
    mesh_.triangles.push_back({at(a), at(b), at(c)});
  }
  void quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 outward) { tri(a, b, c, outward), tri(a, c, d, outward); }
  // A convex planar polygon (boundary in order, collinear runs allowed), fanned from its centroid.
  void fan(const std::vector<Vec3>& ring, Vec3 outward) {
    Vec3 c{0, 0, 0};
    for (Vec3 v : ring) c = c + v;
    c = c * (1.0 / static_cast<double>(ring.size()));
    for (std::size_t i = 0; i < ring.size(); ++i) tri(c, ring[i], ring[(i + 1) % ring.size()], outward);
  }

 private:
  std::uint32_t at(Vec3 p) {
    p = {snap_mm(p.x), snap_mm(p.y), snap_mm(p.z)};  // generated coordinates live on the 1 mm grid
    const auto [it, fresh] = index_.emplace(std::array<double, 3>{p.x, p.y, p.z}, static_cast<std::uint32_t>(mesh_.vertices.size()));
    if (fresh) mesh_.vertices.push_back(p);
    return it->second;
  }
  MeshObject& mesh_;
  std::map<std::array<double, 3>, std::uint32_t> index_;
};

// A box's facade: storeys of equal height, each wall cut into bays with a recessed window in
// the middle of each (or plain walls).
struct FacadeSpec {
  int storeys = 1;
  double bay_width = 3.6;
  double window_share = 0.6;
  double depth = 0.3;
  bool windows = true;
};

// Grid lines along one wall of length `length`: bay edges and window edges; window cells are the
// middle third of each bay.
std::vector<double> wall_columns(double length, const FacadeSpec& f, bool windows) {
  std::vector<double> xs{0.0};
  if (!windows) {
    xs.push_back(length);
    return xs;
  }
  const int bays = std::max(1, static_cast<int>(std::lround(length / f.bay_width)));
  const double bay = length / bays, glazed = f.window_share * bay;
  for (int j = 0; j < bays; ++j) {
    xs.push_back(j * bay + (bay - glazed) / 2);
    xs.push_back(j * bay + (bay + glazed) / 2);
    if (j + 1 < bays) xs.push_back((j + 1) * bay);
  }
  xs.push_back(length);
  return xs;
}

// Grid lines up the facade: each storey's floor, sill and lintel (or floors only).
std::vector<double> facade_rows(double z0, double z1, const FacadeSpec& f) {
  std::vector<double> zs;
  const double storey = (z1 - z0) / f.storeys;
  for (int k = 0; k < f.storeys; ++k) {
    const double floor = z0 + k * storey;
    zs.push_back(floor);
    if (f.windows) {
      const double glazed = f.window_share * storey;
      zs.push_back(floor + (storey - glazed) / 2);
      zs.push_back(floor + (storey + glazed) / 2);
    }
  }
  zs.push_back(z1);
  return zs;
}

bool wall_has_windows(double length, const FacadeSpec& f) { return f.windows && length >= 1.5; }

std::size_t box_triangles(Vec2 lo, Vec2 hi, double z0, double z1, const FacadeSpec& f) {
  const std::size_t rows = facade_rows(z0, z1, f).size() - 1;
  std::size_t total = 0, ring = 0;
  for (double len : {hi.x - lo.x, hi.y - lo.y, hi.x - lo.x, hi.y - lo.y}) {
    const bool w = wall_has_windows(len, f);
    const std::size_t cols = wall_columns(len, f, w).size() - 1;
    total += 2 * rows * cols;
    if (w) total += 8 * static_cast<std::size_t>(f.storeys) * ((cols + 1) / 3);  // a recess replaces a cell: 10 - 2
    ring += cols;
  }
  return total + 2 * ring;  // top and bottom fans
}

// A closed box [lo, hi] x [z0, z1] with its facade.
void relief_box(MeshObject& mesh, Vec2 lo, Vec2 hi, double z0, double z1, const FacadeSpec& f) {
  Solid s(mesh);
  const Vec2 corner[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};  // counter-clockwise seen from above
  const std::vector<double> zs = facade_rows(z0, z1, f);
  // Each wall's length (axis-aligned walls), whether it has windows, and its columns.
  double length[4];
  bool windows[4];
  std::vector<double> columns[4];
  // Recesses stay shallower than half the wall left beside a window, so the recesses of two
  // walls meeting at a corner never touch.
  double depth = f.depth;
  for (int k = 0; k < 4; ++k) {
    length[k] = std::abs(corner[(k + 1) % 4].x - corner[k].x) + std::abs(corner[(k + 1) % 4].y - corner[k].y);
    windows[k] = wall_has_windows(length[k], f);
    columns[k] = wall_columns(length[k], f, windows[k]);
    if (windows[k]) depth = std::min(depth, 0.45 * columns[k][1]);
  }
  std::vector<Vec3> top, bottom;
  for (int k = 0; k < 4; ++k) {
    const Vec2 a = corner[k], b = corner[(k + 1) % 4];
    const Vec2 u{(b.x - a.x) / length[k], (b.y - a.y) / length[k]};
    const Vec3 n = cross(Vec3{u.x, u.y, 0.0}, kUp);  // outward (walls run counter-clockwise)
    const std::vector<double>& xs = columns[k];
    // Positions along the wall, the ends exactly the shared corners.
    auto plan_at = [&](std::size_t i) {
      if (i == 0) return a;
      if (i + 1 == xs.size()) return b;
      return Vec2{a.x + u.x * xs[i], a.y + u.y * xs[i]};
    };
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
      const Vec2 p0 = plan_at(i), p1 = plan_at(i + 1);
      top.push_back({p0.x, p0.y, z1});
      bottom.push_back({p0.x, p0.y, z0});
      const bool window_column = windows[k] && i % 3 == 1;
      for (std::size_t j = 0; j + 1 < zs.size(); ++j) {
        const Vec3 A{p0.x, p0.y, zs[j]}, B{p1.x, p1.y, zs[j]}, C{p1.x, p1.y, zs[j + 1]}, D{p0.x, p0.y, zs[j + 1]};
        if (!(window_column && j % 3 == 1)) {
          s.quad(A, B, C, D, n);
          continue;
        }
        const Vec3 in = n * -depth;  // the recess: back, sill, lintel and both jambs
        const Vec3 Ab = A + in, Bb = B + in, Cb = C + in, Db = D + in;
        const Vec3 along{u.x, u.y, 0.0};
        s.quad(Ab, Bb, Cb, Db, n);
        s.quad(A, B, Bb, Ab, kUp);
        s.quad(D, C, Cb, Db, kUp * -1.0);
        s.quad(A, D, Db, Ab, along);
        s.quad(B, C, Cb, Bb, along * -1.0);
      }
    }
  }
  s.fan(top, kUp);
  s.fan(bottom, kUp * -1.0);
}

// A gable (hipped = false) or hipped roof on [lo, hi] at z, the ridge `rise` higher along the
// longer side; a pyramid when a hipped roof's ridge would vanish.
void roof(MeshObject& mesh, Vec2 lo, Vec2 hi, double z, double rise, bool hipped) {
  Solid s(mesh);
  const bool along_x = hi.x - lo.x >= hi.y - lo.y;
  // Local (u along the ridge, v across) to world, for points and directions alike.
  auto at = [&](double u, double v, double h) { return along_x ? Vec3{u, v, h} : Vec3{v, u, h}; };
  const double u0 = along_x ? lo.x : lo.y, u1 = along_x ? hi.x : hi.y, v0 = along_x ? lo.y : lo.x, v1 = along_x ? hi.y : hi.x;
  const double vm = (v0 + v1) / 2, half = (v1 - v0) / 2;
  const Vec3 c0 = at(u0, v0, z), c1 = at(u1, v0, z), c2 = at(u1, v1, z), c3 = at(u0, v1, z);
  s.quad(c0, c1, c2, c3, kUp * -1.0);
  const double r0 = hipped ? u0 + half : u0, r1 = hipped ? u1 - half : u1;
  if (hipped && r1 - r0 < 0.05) {  // a pyramid
    const Vec3 apex = at((u0 + u1) / 2, vm, z + rise);
    s.tri(c0, c1, apex, at(0, -1, 1)), s.tri(c1, c2, apex, at(1, 0, 1)), s.tri(c2, c3, apex, at(0, 1, 1)), s.tri(c3, c0, apex, at(-1, 0, 1));
    return;
  }
  const Vec3 R0 = at(r0, vm, z + rise), R1 = at(r1, vm, z + rise);
  s.quad(c0, c1, R1, R0, at(0, -1, 1));
  s.quad(c3, c2, R1, R0, at(0, 1, 1));
  s.tri(c0, R0, c3, at(-1, 0, hipped ? 1 : 0));
  s.tri(c1, R1, c2, at(1, 0, hipped ? 1 : 0));
}

// The facade spec for a box, its bays widened (then its windows dropped) until the box fits
// `budget` triangles.
FacadeSpec fitted(Vec2 lo, Vec2 hi, double z0, double z1, FacadeSpec f, std::size_t budget) {
  for (int i = 0; i < 12 && box_triangles(lo, hi, z0, z1, f) > budget; ++i) f.bay_width *= 1.5;
  if (box_triangles(lo, hi, z0, z1, f) > budget) f.windows = false;
  while (f.storeys > 1 && box_triangles(lo, hi, z0, z1, f) > budget) f.storeys = std::max(1, f.storeys / 2);
  return f;
}

}  // namespace

void validate(const DetailedCityParams& p, const std::string& generator) {
  validate(p.layout, generator);
  const ParamChecks check("generator", generator);
  check.in_range("storey_height", p.storey_height, 2.0, 10.0);
  check.in_range("bay_width", p.bay_width, 1.0, 50.0);
  check.in_range("window_share", p.window_share, 0.1, 0.9);
  check.in_range("window_depth", p.window_depth, 0.01, 2.0);
  check.in_range("tower_fraction", p.tower_fraction, 0.0, 1.0);
  check.in_range("pitched_fraction", p.pitched_fraction, 0.0, 1.0);
  check.in_range("hipped_fraction", p.hipped_fraction, 0.0, 1.0 - p.pitched_fraction);
  check.in_range("arcade_fraction", p.arcade_fraction, 0.0, 1.0);
  check.in_range("plain_fraction", p.plain_fraction, 0.0, 1.0);
  check.in_range("max_triangles", p.max_triangles, 200, 1'000'000);
}

MeshObject detailed_building(ObjectId id, Vec2 lo, Vec2 hi, double height, const DetailedCityParams& p, std::uint64_t seed) {
  Random rng = Random::stream(seed, 0xde7a11, id);
  MeshObject m;
  m.id = id;
  m.name = "building " + std::to_string(id);
  const double w = hi.x - lo.x, d = hi.y - lo.y, thin = std::min(w, d);
  FacadeSpec f;
  // Facades differ in grain: bays up to six times the nominal width (mostly narrow), so triangle
  // counts spread from about a hundred to the cap. Plain arithmetic, no libm: the same on every build.
  const double grain = rng.uniform01();
  f.bay_width = p.bay_width * (1.0 + 5.0 * grain * grain);
  f.window_share = p.window_share;
  f.depth = std::min(p.window_depth, 0.25 * thin);
  const double draw_kind = rng.uniform01(), draw_roof = rng.uniform01(), draw_arcade = rng.uniform01();
  const bool tower = height > 25 && thin > 12 && draw_kind < p.tower_fraction;
  const bool pitched = !tower && height <= 25 && draw_roof < p.pitched_fraction;
  const bool hipped = !tower && height <= 25 && !pitched && draw_roof < p.pitched_fraction + p.hipped_fraction;
  const double rise = (pitched || hipped) ? std::min({4.0, 0.3 * thin, 0.3 * height}) : 0.0;
  const double body = height - rise;  // the walls' top
  const int storeys = std::max(1, static_cast<int>(std::lround(body / p.storey_height)));
  f.windows = body / storeys >= 2.0 && rng.uniform01() >= p.plain_fraction;
  const bool arcade = storeys >= 2 && d >= 8 && draw_arcade < p.arcade_fraction;
  const std::size_t budget = static_cast<std::size_t>(p.max_triangles);
  const double storey = body / storeys;
  double base = 0.0;  // where the main body starts (above an arcade)
  std::size_t used = 0;
  if (arcade) {  // the ground storey set back behind columns, under the storey above
    const double depth = std::min(3.0, 0.3 * d), column = 0.4;
    FacadeSpec ground = f;
    ground.storeys = 1;
    ground = fitted({lo.x, lo.y + depth}, hi, 0.0, storey, ground, budget / 4);
    relief_box(m, {lo.x, lo.y + depth}, hi, 0.0, storey, ground);
    const int columns = std::max(2, static_cast<int>(std::lround(w / 4.0)) + 1);
    FacadeSpec plain;
    plain.windows = false;
    for (int k = 0; k < columns; ++k) {
      const double x = lo.x + (w - column) * k / (columns - 1);
      relief_box(m, {x, lo.y}, {x + column, lo.y + column}, 0.0, storey, plain);
    }
    base = storey;
    used = m.triangles.size();
  }
  const int upper_storeys = storeys - (arcade ? 1 : 0);
  if (tower) {  // a podium of 2-4 storeys, the tower set back on it
    const int podium = std::min(upper_storeys - 1, 2 + static_cast<int>(rng.uniform_int(0, 2)));
    const double top_podium = base + podium * storey;
    const double inset = thin * rng.uniform_real(0.15, 0.3);
    FacadeSpec pf = f, tf = f;
    pf.storeys = podium, tf.storeys = upper_storeys - podium;
    const std::size_t left = budget > used ? budget - used : 0;
    pf = fitted(lo, hi, base, top_podium, pf, left / 3);
    relief_box(m, lo, hi, base, top_podium, pf);
    const Vec2 tlo{lo.x + inset, lo.y + inset}, thi{hi.x - inset, hi.y - inset};
    tf = fitted(tlo, thi, top_podium, body, tf, budget > m.triangles.size() ? budget - m.triangles.size() : 0);
    relief_box(m, tlo, thi, top_podium, body, tf);
  } else {
    FacadeSpec bf = f;
    bf.storeys = upper_storeys;
    const std::size_t roof_triangles = rise > 0 ? 8 : 0;
    bf = fitted(lo, hi, base, body, bf, budget > used + roof_triangles ? budget - used - roof_triangles : 0);
    relief_box(m, lo, hi, base, body, bf);
    if (rise > 0) roof(m, lo, hi, body, rise, hipped);
  }
  for (const Vec3& v : m.vertices) m.bounds.extend(v);
  m.closed = true;  // every solid is closed (tested: finish_mesh agrees)
  return m;
}

Scene detailed_city(const DetailedCityParams& p, std::uint64_t seed) {
  validate(p);
  const Scene layout = p.layout.plaza_blocks_x > 0 ? plaza_city(p.layout, seed) : manhattan_city(p.layout, seed);
  Scene s;
  s.provenance = {"detailed", seed, params_to_json(p).dump()};
  s.meshes.reserve(layout.buildings.size());
  for (const Building& b : layout.buildings) {
    const Box2 box = b.bounds.plan();
    s.meshes.push_back(detailed_building(b.id, box.lo, box.hi, b.height, p, seed));
  }
  return s;
}

}  // namespace cullcheck::generators
