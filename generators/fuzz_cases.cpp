// Bodies of the fuzzer's generators declared in fuzz_cases.hpp (compiled once, as
// rapidcheck_gens.cpp explains).

#include "generators/fuzz_cases.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

namespace cullcheck::generators::rcgen {

rc::Gen<SceneSpec> openings_spec() {
  using detail::int_in;
  return detail::spec_of("openings", rc::gen::map(rc::gen::tuple(int_in(1, 2), int_in(1, 2), int_in(0, 10), int_in(0, 10), int_in(0, 2),
                                                                 int_in(1, 4)),
                                                  [](const std::tuple<int, int, int, int, int, int>& t) {
                                                    const auto [bx, by, facades, arcades, bridges, core] = t;
                                                    return nlohmann::json{{"blocks_x", bx},
                                                                          {"blocks_y", by},
                                                                          {"core_buildings", core},
                                                                          {"facade_weight", 0.1 + facades / 10.0},
                                                                          {"arcade_weight", 0.1 + arcades / 10.0},
                                                                          {"plain_weight", 0.2},
                                                                          {"bridge_count", bridges}};
                                                  }));
}

rc::Gen<SceneSpec> fuzz_scene_spec() {
  return rc::gen::weightedOneOf<SceneSpec>(
      {{3, manhattan_spec()}, {2, scatter_spec()}, {2, irregular_spec()}, {1, plaza_spec()}, {1, thesis_spec()}, {3, openings_spec()}});
}

namespace detail {

// Every object's bounding box, buildings then meshes.
std::vector<Box3> object_boxes(const Scene& scene) {
  std::vector<Box3> boxes;
  for (const Building& b : scene.buildings) boxes.push_back(b.bounds);
  for (const MeshObject& m : scene.meshes) boxes.push_back(m.bounds);
  return boxes;
}

double elevation_of(Vec3 d) { return std::atan2(d.z, std::sqrt(d.x * d.x + d.y * d.y)); }

}  // namespace detail

rc::Gen<CameraPath> viewport_edge_path(const Scene& scene) {
  using detail::int_in;
  const auto shared = std::make_shared<const detail::SharedScene>(scene);
  return rc::gen::map(rc::gen::tuple(camera_in(scene), int_in(0, 1 << 20), int_in(0, 7), int_in(0, 3), int_in(1, 200)),
                      [shared](const std::tuple<Camera, int, int, int, int>& t) {
                        auto [c, object, corner, edge, inside_centi_degrees] = t;
                        CameraPath path;
                        path.kind = "viewport_edge";
                        const std::vector<Box3> boxes = detail::object_boxes(shared->scene);
                        if (c.omnidirectional()) c.hfov = kPi / 3, c.vfov = kPi / 4;
                        if (!boxes.empty()) {
                          const Box3& b = boxes[static_cast<std::size_t>(object) % boxes.size()];
                          const Vec3 p{corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y, corner & 4 ? b.hi.z : b.lo.z};
                          const Vec3 d = p - c.position;
                          const double inside = radians(inside_centi_degrees / 100.0);
                          c.roll = 0.0;
                          c.yaw = azimuth_of({d.x, d.y});
                          c.pitch = std::clamp(detail::elevation_of(d), -kPi / 2 + 0.05, kPi / 2 - 0.05);
                          // The corner at the edge: turn the view away from it by half the field of view, less `inside`.
                          if (edge == 0) c.yaw += c.hfov / 2 - inside;
                          if (edge == 1) c.yaw -= c.hfov / 2 - inside;
                          if (edge == 2) c.pitch = std::clamp(c.pitch - (c.vfov / 2 - inside), -kPi / 2, kPi / 2);
                          if (edge == 3) c.pitch = std::clamp(c.pitch + (c.vfov / 2 - inside), -kPi / 2, kPi / 2);
                          c.yaw = std::fmod(c.yaw + 2 * kTwoPi, kTwoPi);
                        }
                        path.frames.push_back(c);
                        return path;
                      });
}

rc::Gen<CameraPath> lateral_path(const Scene& scene) {
  using detail::int_in;
  return rc::gen::map(rc::gen::tuple(street_camera(scene), int_in(1, 6), int_in(5, 300), rc::gen::arbitrary<bool>(), int_in(0, 30)),
                      [](const std::tuple<Camera, int, int, bool, int>& t) {
                        auto [c, steps, centimetres, left, turn_tenths] = t;
                        CameraPath path;
                        path.kind = "lateral";
                        if (c.omnidirectional()) c.hfov = kPi / 3, c.vfov = kPi / 4;
                        for (int k = 0; k <= steps; ++k) {
                          path.frames.push_back(c);
                          const Vec3 right = basis_of(c).right;
                          const double s = (left ? -1.0 : 1.0) * centimetres / 100.0;
                          c.position = c.position + Vec3{right.x, right.y, 0.0} * s;
                          c.yaw = std::fmod(c.yaw + radians(turn_tenths / 10.0) + kTwoPi, kTwoPi);
                        }
                        return path;
                      });
}

rc::Gen<CameraPath> tilted_path(const Scene& scene) {
  using detail::int_in;
  return rc::gen::map(rc::gen::tuple(camera_in(scene), detail::signed_grid(890, radians(0.1)), detail::signed_grid(1800, radians(0.1))),
                      [](const std::tuple<Camera, double, double>& t) {
                        auto [c, pitch, roll] = t;
                        if (c.omnidirectional()) c.hfov = kPi / 2, c.vfov = kPi / 3;
                        c.pitch = pitch, c.roll = roll;
                        CameraPath path;
                        path.kind = "tilted";
                        path.frames.push_back(c);
                        return path;
                      });
}

rc::Gen<CameraPath> orthographic_path(const Scene& scene) {
  using detail::int_in;
  return rc::gen::map(rc::gen::tuple(camera_in(scene), int_in(2, 400), int_in(50, 200), rc::gen::arbitrary<bool>()),
                      [](const std::tuple<Camera, int, int, bool>& t) {
                        auto [c, width, aspect_percent, top_down] = t;
                        c.projection = Projection::orthographic;
                        c.ortho_width = width;
                        c.ortho_height = width * aspect_percent / 100.0;
                        if (top_down) c.pitch = -kPi / 2;
                        c.near = 0.0;
                        CameraPath path;
                        path.kind = "orthographic";
                        path.frames.push_back(c);
                        return path;
                      });
}

rc::Gen<CameraPath> near_plane_path(const Scene& scene) {
  using detail::int_in;
  const auto shared = std::make_shared<const detail::SharedScene>(scene);
  return rc::gen::map(rc::gen::tuple(int_in(0, 1 << 20), int_in(0, 3), int_in(2, 100), int_in(1, 50), int_in(-900, 900), field_of_view()),
                      [shared](const std::tuple<int, int, int, int, int, FieldOfView>& t) {
                        auto [object, side, distance_cm, near_cm, turn_tenths, fov] = t;
                        Camera c;
                        if (fov.hfov < kTwoPi) c.hfov = fov.hfov, c.vfov = fov.vfov;
                        c.near = near_cm / 100.0;
                        const std::vector<Box3> boxes = detail::object_boxes(shared->scene);
                        Box3 b{{-1, -1, 0}, {1, 1, 3}};
                        if (!boxes.empty()) b = boxes[static_cast<std::size_t>(object) % boxes.size()];
                        const double mx = (b.lo.x + b.hi.x) / 2, my = (b.lo.y + b.hi.y) / 2, d = distance_cm / 100.0;
                        const Vec2 at[4] = {{b.lo.x - d, my}, {b.hi.x + d, my}, {mx, b.lo.y - d}, {mx, b.hi.y + d}};
                        const double facing[4] = {0.0, kPi, kPi / 2, 3 * kPi / 2};
                        c.position = {at[side].x, at[side].y, std::clamp(1.7, b.lo.z + 0.1, std::max(b.lo.z + 0.1, b.hi.z - 0.1))};
                        c.yaw = std::fmod(facing[side] + radians(turn_tenths / 10.0) + kTwoPi, kTwoPi);
                        CameraPath path;
                        path.kind = "near_plane";
                        path.frames.push_back(c);
                        return path;
                      });
}

rc::Gen<CameraPath> street_path(const Scene& scene) {
  return rc::gen::map(rc::gen::container<std::vector<Camera>>(2, camera_in(scene)), [](std::vector<Camera> cams) {
    CameraPath path;
    path.kind = "street";
    path.frames = std::move(cams);
    return path;
  });
}

rc::Gen<FuzzCase> fuzz_case(rc::Gen<SceneSpec> specs, bool orthographic) {
  return rc::gen::mapcat(std::move(specs), [orthographic](const SceneSpec& spec) {
    const Scene scene = scene_of(spec);
    auto paths = orthographic ? rc::gen::weightedOneOf<CameraPath>({{4, viewport_edge_path(scene)},
                                                                    {2, lateral_path(scene)},
                                                                    {2, tilted_path(scene)},
                                                                    {2, near_plane_path(scene)},
                                                                    {1, street_path(scene)},
                                                                    {2, orthographic_path(scene)}})
                              : rc::gen::weightedOneOf<CameraPath>({{4, viewport_edge_path(scene)},
                                                                    {2, lateral_path(scene)},
                                                                    {2, tilted_path(scene)},
                                                                    {2, near_plane_path(scene)},
                                                                    {1, street_path(scene)}});
    return rc::gen::map(std::move(paths), [spec](CameraPath path) {
      path.frames_per_second = 30.0;
      return FuzzCase{spec, path.kind, std::move(path)};
    });
  });
}

}  // namespace cullcheck::generators::rcgen
