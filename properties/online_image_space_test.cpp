// On-line image-space culling (Wang, Agarwal & Har-Peled 2001; engine/online_image_space/):
// unit cases for its parts (kd-tree, rasteriser, erosion, hierarchy, occlusion test, occluder
// selection, critical frames) with literal expectations, and the method held to the pixel
// oracle along generated walks.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include "core/errors.hpp"
#include "core/scene_timeline.hpp"
#include "engine/method.hpp"
#include "engine/online_image_space/occluder_selection.hpp"
#include "engine/online_image_space/occlusion_mask.hpp"
#include "engine/online_image_space/online_culling.hpp"
#include "engine/online_image_space/polygon_kd_tree.hpp"
#include "generators/camera_paths.hpp"
#include "generators/camera_moves.hpp"
#include "generators/city.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "generators/scene_timeline_gen.hpp"
#include "oracle/oracle.hpp"
#include "properties/property_run.hpp"
#include "reports/verification.hpp"

namespace cullcheck {
namespace {

// A camera at (0, 0, 10) looking along +x with 90-degree fields of view: the image plane at
// depth 1 spans [-1, 1] each way, so with s = 64 one pixel is 1/32 of it.
Camera square_camera() {
  Camera c;
  c.position = {0, 0, 10};
  c.hfov = c.vfov = kPi / 2;
  c.near = 0.1;
  c.far = 1000;
  return c;
}

// A 10 m x 10 m wall facing the camera at x = 10, centred on the view axis.
std::vector<Vec3> facing_wall(double x = 10) { return {{x, 5, 5}, {x, -5, 5}, {x, -5, 15}, {x, 5, 15}}; }

Scene one_box_scene(std::vector<std::pair<Box2, double>> boxes) {
  Scene scene;
  ObjectId id = 0;
  for (const auto& [b, h] : boxes) {
    Building building;
    building.id = id++;
    building.footprint = {b.lo, {b.hi.x, b.lo.y}, b.hi, {b.lo.x, b.hi.y}};
    building.height = h;
    finish_building(building);
    scene.buildings.push_back(building);
  }
  return scene;
}

TEST(OnlineImagePlane, SquarePixelsAcrossTheFieldOfViewAndItsWidening) {
  const online::ImagePlane plain(square_camera(), 64);
  EXPECT_EQ(plain.width(), 64);
  EXPECT_EQ(plain.height(), 64);
  // Widened by 0.15 rad each side at the same pixel size, plus 7 guard pixels: tan(45 deg + 0.15)
  // = 1.3506 of the plane, 43.2 -> 44 pixels of 1/32 each side beyond the centre... 2 * 44 + 14.
  const online::ImagePlane wide(square_camera(), 64, 0.15, 7);
  EXPECT_EQ(wide.width(), 2 * 44 + 14);
  EXPECT_EQ(wide.guard(), 7);
  const online::ViewPoint centre = plain.project(plain.to_camera({20, 0, 10}));
  EXPECT_DOUBLE_EQ(centre.x, 32.0);
  EXPECT_DOUBLE_EQ(centre.y, 32.0);
  EXPECT_DOUBLE_EQ(centre.depth, 20.0);
  // The smallest angle of one pixel is at the image's corners, below the centre's 1/32 rad.
  EXPECT_LT(plain.smallest_pixel_angle(), 1.0 / 32);
  EXPECT_NEAR(plain.smallest_pixel_angle(), (1.0 / 32) * std::sqrt(2.0) / 3.0, 1e-12);
}

// A 0.6-degree field of view widened by 0.15 rad would need a mask 50 times as wide: each
// half-extent is capped at s pixels, and then the clip region no longer holds the view.
TEST(OnlineImagePlane, ANarrowViewGetsACappedMaskThatSaysSo) {
  Camera narrow = square_camera();
  narrow.hfov = narrow.vfov = 0.01;
  const online::ImagePlane plane(narrow, 256, 0.15, 7);
  EXPECT_EQ(plane.width(), 2 * 256 + 14);
  EXPECT_EQ(plane.height(), 2 * 256 + 14);
  EXPECT_FALSE(plane.covers_view());
  EXPECT_TRUE(online::ImagePlane(square_camera(), 64, 0.15, 7).covers_view());
}

// A roof of a hundred vertices (a round building's one convex prism) is drawn like any polygon.
TEST(OnlineOcclusionMask, DrawsPolygonsOfManyVertices) {
  const online::ImagePlane plane(square_camera(), 64);
  online::DepthImage depth(plane);
  std::vector<Vec3> disc;
  for (int i = 0; i < 100; ++i) disc.push_back({10, 4 * std::cos(2 * kPi * i / 100), 10 + 4 * std::sin(2 * kPi * i / 100)});
  // A disc of radius 0.4 of the plane: about pi 12.8^2 = 515 pixel centres.
  const std::uint64_t written = depth.draw(disc.data(), 100);
  EXPECT_GT(written, 490u);
  EXPECT_LT(written, 540u);  // 524: the lattice count of a disc strays a few percent
}

TEST(OnlineOcclusionMask, RasterisesErodesAndTestsAWallFacingTheCamera) {
  const online::ImagePlane plane(square_camera(), 64);
  online::DepthImage depth(plane);
  const std::vector<Vec3> wall = facing_wall();
  // The wall spans [-0.5, 0.5] of the plane each way: pixels 16..47, 32 x 32 of them, all at depth 10.
  EXPECT_EQ(depth.draw(wall.data(), 4), 32u * 32u);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const double d = depth.depth()[std::size_t(j * 64 + i)];
      if (i >= 16 && i < 48 && j >= 16 && j < 48) {
        EXPECT_DOUBLE_EQ(d, 10.0) << i << "," << j;
      } else {
        EXPECT_TRUE(std::isinf(d)) << i << "," << j;
      }
    }
  // Δ = 2: erosion by 3 pixels leaves 26 x 26.
  online::OcclusionMask mask(plane, depth, 2);
  EXPECT_EQ(mask.covered_pixels(), 26u * 26u);
  mask.build_hierarchy(2, -1);
  ASSERT_EQ(mask.level_count(), 7u);  // 64, 32, 16, 8, 4, 2, 1
  EXPECT_TRUE(std::isinf(mask.level(6)[0]));
  for (std::size_t l = 1; l < mask.level_count(); ++l) {  // each coarse pixel is the max of its 2 x 2
    const int w = 64 >> l, fw = 64 >> (l - 1);
    for (int j = 0; j < w; ++j)
      for (int i = 0; i < w; ++i) {
        double m = 0;
        for (int k = 0; k < 4; ++k) m = std::max(m, mask.level(l - 1)[std::size_t((2 * j + k / 2) * fw + 2 * i + k % 2)]);
        EXPECT_EQ(mask.level(l)[std::size_t(j * w + i)], m);
      }
  }
  Box3 behind{{20, -1, 9}, {21, 1, 11}};
  EXPECT_TRUE(mask.occluded(behind));
  // Reaching 0.42 of the plane sideways at depth 20 (pixel 18.6 from the left): inside the wall
  // but within the 3 eroded pixels of its edge (pixel 19 is the first kept one).
  Box3 near_edge{{20, -1, 9}, {21, 8.4, 11}};
  EXPECT_FALSE(mask.occluded(near_edge));
  Box3 in_front{{5, -1, 9}, {6, 1, 11}};
  EXPECT_FALSE(mask.occluded(in_front));
  Box3 around_the_eye{{-1, -1, 9}, {30, 1, 11}};
  EXPECT_FALSE(mask.occluded(around_the_eye));
  Box3 touching_the_wall{{10, -1, 9}, {21, 1, 11}};  // nearest depth 10 is not behind 10
  EXPECT_FALSE(mask.occluded(touching_the_wall));
}

TEST(OnlineOcclusionMask, ATiltedPolygonKeepsItsDeepestCornerPerPixel) {
  // A floor-like quad seen from above at a slant: every pixel's value must bound the plane's
  // depth over the pixel's whole square, so it is at least the depth at the pixel's centre.
  const online::ImagePlane plane(square_camera(), 64);
  online::DepthImage depth(plane);
  const std::vector<Vec3> slope{{10, -5, 5}, {30, -5, 5}, {30, 5, 12}, {10, 5, 12}};
  ASSERT_GT(depth.draw(slope.data(), 4), 0u);
  const Vec3 a = plane.to_camera(slope[0]), b = plane.to_camera(slope[1]), c = plane.to_camera(slope[3]);
  const Vec3 n = cross(b - a, c - a);
  int checked = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const double d = depth.depth()[std::size_t(j * 64 + i)];
      if (std::isinf(d)) continue;
      const Vec3 dir = plane.direction(i + 0.5, j + 0.5);
      const double at_centre = dot(n, a) / dot(n, dir);  // depth along the ray (z of dir is 1)
      EXPECT_GE(d, at_centre * (1 - 1e-12));
      ++checked;
    }
  EXPECT_GT(checked, 50);
}

TEST(OnlineOcclusionMask, TheGroundFillsTheImageBelowTheHorizonOnly) {
  const online::ImagePlane plane(square_camera(), 64);
  online::DepthImage depth(plane);
  // A level camera: the lower half's pixel centres see the ground, the upper half's do not.
  EXPECT_EQ(depth.draw_ground(1000), 32u * 64u);
  // Row 63 (centre 0.5 px from the bottom, 31.5/32 of the plane below the axis): depth 10 / (31.5/32).
  EXPECT_NEAR(depth.depth()[63 * 64], 10.0 / (31.0 / 32.0), 1e-9);  // deepest corner: the row's top edge
  EXPECT_DOUBLE_EQ(depth.depth()[32 * 64], 1000.0);  // the row under the horizon: its top corners are on it
}

TEST(OnlineKdTree, LeavesHoldAtMostRhoPolygonsAndBoxesBoundThem) {
  const Scene scene = generators::default_city(1);
  const online::ScenePolygons polygons = online::scene_polygons(scene);
  EXPECT_EQ(polygons.size(), 14040u);  // walls and roofs of the default city
  online::PolygonKdTree tree(polygons, 16);
  const auto check = [&](std::size_t expected) {
    std::vector<int> seen(polygons.size(), 0);
    for (std::size_t n = 0; n < tree.nodes().size(); ++n) {
      const auto& node = tree.nodes()[n];
      if (node.parent < 0 && n != 0) continue;  // not reachable
      if (node.leaf()) {
        EXPECT_LE(node.polygons.size(), 2u * 16u);
        EXPECT_EQ(node.count, node.polygons.size());
        EXPECT_TRUE(std::is_sorted(node.polygons.begin(), node.polygons.end()));
        for (std::uint32_t p : node.polygons) {
          ++seen[p];
          for (std::int32_t a = std::int32_t(n); a >= 0; a = tree.nodes()[std::size_t(a)].parent) {
            const Box3& b = tree.nodes()[std::size_t(a)].box;
            EXPECT_TRUE(b.lo.x <= polygons.box[p].lo.x && b.hi.x >= polygons.box[p].hi.x && b.lo.z <= polygons.box[p].lo.z &&
                        b.hi.z >= polygons.box[p].hi.z);
          }
        }
      } else {
        EXPECT_EQ(node.count, tree.nodes()[std::size_t(node.child[0])].count + tree.nodes()[std::size_t(node.child[1])].count);
        EXPECT_EQ(tree.nodes()[std::size_t(node.child[0])].parent, std::int32_t(n));
      }
    }
    EXPECT_EQ(tree.nodes()[0].count, expected);
    std::size_t alive = 0;
    for (std::size_t p = 0; p < polygons.size(); ++p) {
      EXPECT_EQ(seen[p], tree.alive(std::uint32_t(p)) ? 1 : 0) << p;
      alive += tree.alive(std::uint32_t(p)) ? 1 : 0;
    }
    EXPECT_EQ(alive, expected);
  };
  for (const auto& node : tree.nodes())
    if (node.leaf()) {
      EXPECT_LE(node.polygons.size(), 16u);
    }
  check(polygons.size());
  // Section 6: delete a thousand polygons, then put them back; the leaves that overflow split.
  for (std::uint32_t p = 0; p < 14000; p += 14) tree.erase(p);
  check(polygons.size() - 1000);
  const std::size_t nodes_before = tree.nodes().size();
  for (std::uint32_t p = 0; p < 14000; p += 14) tree.insert(p);
  check(polygons.size());
  EXPECT_EQ(tree.nodes().size(), nodes_before);  // every leaf is back to its old size: no split
  EXPECT_THROW(tree.insert(0), std::invalid_argument);
  tree.erase(0);
  EXPECT_THROW(tree.erase(0), std::invalid_argument);
}

TEST(OnlineKdTree, AnOverflowingLeafSplitsInPlace) {
  // One building of 40 walls on a circle: 41 polygons, ρ = 4.
  Scene scene;
  Building b;
  for (int i = 0; i < 40; ++i) b.footprint.push_back({10 * std::cos(2 * kPi * i / 40), 10 * std::sin(2 * kPi * i / 40)});
  b.height = 5;
  finish_building(b);
  scene.buildings.push_back(b);
  online::ScenePolygons polygons = online::scene_polygons(scene);
  const std::size_t n = polygons.size();
  online::PolygonKdTree tree(polygons, 4);
  for (std::uint32_t p = 0; p < n; ++p) tree.erase(p);
  EXPECT_EQ(tree.nodes()[0].count, 0u);
  for (std::uint32_t p = 0; p < n; ++p) tree.insert(p);
  EXPECT_EQ(tree.nodes()[0].count, n);
  for (const auto& node : tree.nodes())
    if (node.leaf()) {
      EXPECT_LE(node.polygons.size(), 8u);
    }
}

TEST(OnlineOccluderSelection, ChoosesNothingNearerThanDAndStopsAtR) {
  const Scene scene = generators::default_city(1);
  generators::StreetWalkParams walk;
  walk.frames = 1;
  const Camera camera = generators::street_walk(scene, walk, 1).frames[0];
  const online::ScenePolygons polygons = online::scene_polygons(scene);
  const online::PolygonKdTree tree(polygons, 16);
  const online::ImagePlane plane(camera, 256);
  const ViewVolume volume(camera);
  for (const auto priority : {online::OccluderPriority::distance, online::OccluderPriority::coverage}) {
    online::SelectionParameters p;
    p.occluders = 300;
    p.min_distance = 40;
    p.priority = priority;
    const online::OccluderSelection chosen = online::select_occluders(tree, polygons, plane, volume, p);
    EXPECT_GE(chosen.polygons.size(), 300u);
    EXPECT_LT(chosen.polygons.size(), 300u + 16u);  // the last node chosen brings at most ρ
    for (std::uint32_t q : chosen.polygons) EXPECT_GE(online::min_distance(camera.position, polygons.box[q]), 40.0);
    EXPECT_GE(chosen.nearest, 40.0);
  }
}

// Two buildings on the x axis: a wide slab 60 m ahead and a small block 200 m ahead behind it.
Scene slab_and_block() { return one_box_scene({{{{60, -100}, {62, 100}}, 30.0}, {{{200, -2}, {204, 2}}, 10.0}}); }
// ρ = 1: every polygon its own leaf, so the slab's box is never one with the block's.
OnlineCullingOptions fine_leaves() {
  OnlineCullingOptions o;
  o.leaf_size = 1;
  return o;
}
Camera walker_at(double x) {
  Camera c;
  c.position = {x, 0, 1.7};
  c.near = 0.5;
  c.far = 2000;
  return c;
}

TEST(OnlineCulling, EquationOneAsPublishedAndGuarded) {
  const Scene scene = slab_and_block();
  OnlineImageSpaceCulling published(scene, OnlineImageSpaceCulling::Variant::published);
  OnlineImageSpaceCulling guarded(scene, OnlineImageSpaceCulling::Variant::guarded);
  Camera c = walker_at(0);  // hfov 60 degrees, s = 256, Δ = 6
  // δ = 2 Δ D / (s tan(θ/2)) = 12 * 100 / (256 tan 30 deg).
  EXPECT_NEAR(published.delta_for(c, 100), 8.118988160479113, 1e-12);
  // D sin(Δ ω): ω of a 368 x 282 pixel plane (60 x 45 degrees widened by 0.15 rad, 7 guard pixels).
  EXPECT_NEAR(guarded.delta_for(c, 100), 1.5321231869849616, 1e-9);
}

TEST(OnlineCulling, CriticalFramesComeExactlyWhenPublished) {
  const Scene scene = slab_and_block();
  OnlineImageSpaceCulling method(scene, OnlineImageSpaceCulling::Variant::published, fine_leaves());
  method.set_frame(0, 0.0);
  CullResult r = method.cull(walker_at(0));
  EXPECT_EQ(method.last_frame().critical, CriticalReason::first);
  EXPECT_EQ(r.pvs, std::vector<ObjectId>{0});  // the block hides behind the slab
  EXPECT_NEAR(method.last_frame().nearest_occluder, 60.0, 1e-9);
  const double stamp = method.last_frame().stamp;
  EXPECT_NEAR(stamp, method.delta_for(walker_at(0), 60.0) / 2.0, 1e-12);  // t + δ / V, V = 2 m/s
  method.set_frame(1, stamp * 0.99);
  r = method.cull(walker_at(0.5));
  EXPECT_EQ(method.last_frame().critical, CriticalReason::none);
  EXPECT_EQ(r.pvs, std::vector<ObjectId>{0});
  EXPECT_EQ(r.stats.items_skipped, 5u);  // the block's 4 walls and roof, under stamped nodes
  method.set_frame(2, stamp);  // "real time reaches the value of the time stamp"
  method.cull(walker_at(0.5));
  EXPECT_EQ(method.last_frame().critical, CriticalReason::expired);
  Camera turned = walker_at(0.5);
  turned.yaw = 0.2;  // beyond critical_turn 0.15
  method.set_frame(3, stamp * 1.01);
  method.cull(turned);
  EXPECT_EQ(method.last_frame().critical, CriticalReason::turned);
  method.cull(turned);  // no set_frame: a query outside a path starts afresh
  EXPECT_EQ(method.last_frame().critical, CriticalReason::first);
}

TEST(OnlineCulling, TheGuardedVariantRemarksWhenTheEyeLeavesItsBall) {
  const Scene scene = slab_and_block();
  OnlineImageSpaceCulling method(scene, OnlineImageSpaceCulling::Variant::guarded);
  method.set_frame(0, 0.0);
  method.cull(walker_at(0));
  const double delta = method.last_frame().delta;
  EXPECT_NEAR(delta, method.delta_for(walker_at(0), 60.0), 1e-12);
  method.set_frame(1, 1e-6);
  method.cull(walker_at(delta * 0.9));
  EXPECT_EQ(method.last_frame().critical, CriticalReason::none);
  method.set_frame(2, 2e-6);  // far too fast for V, and the clock alone would not notice
  method.cull(walker_at(delta * 1.1));
  EXPECT_EQ(method.last_frame().critical, CriticalReason::left_ball);
}

TEST(OnlineCulling, DeltaZeroMarksEveryFrameAndStillCulls) {
  const Scene scene = slab_and_block();
  OnlineCullingOptions o = fine_leaves();
  o.shrink_pixels = 0;
  OnlineImageSpaceCulling method(scene, OnlineImageSpaceCulling::Variant::published, o);
  for (int f = 0; f < 3; ++f) {
    method.set_frame(std::size_t(f), f / 30.0);
    EXPECT_EQ(method.cull(walker_at(f * 0.05)).pvs, std::vector<ObjectId>{0});
    EXPECT_NE(method.last_frame().critical, CriticalReason::none);
  }
}

// Section 6: deleting the occluder makes the next frame critical and shows what it hid; an
// object inserted where the tree's nodes carry stamps is sent, not hidden untested.
TEST(OnlineCulling, DynamicScenesDeleteAnOccluderAndInsertBehindIt) {
  const Scene scene = slab_and_block();
  OnlineCullingOptions o = fine_leaves();
  o.occluders = 3;  // the leaf of the slab's front wall (its anchor holds three polygons): the block is no occluder
  OnlineImageSpaceCulling method(scene, OnlineImageSpaceCulling::Variant::published, o);
  method.set_frame(0, 0.0);
  EXPECT_EQ(method.cull(walker_at(0)).pvs, std::vector<ObjectId>{0});
  // A new building right behind the block, inside the stamped nodes' region.
  Building late = one_box_scene({{{{210, -2}, {214, 2}}, 10.0}}).buildings[0];
  late.id = 7;
  method.insert_object(late);
  EXPECT_THROW(method.insert_object(late), std::invalid_argument);
  method.set_frame(1, 0.001);
  std::vector<ObjectId> pvs = method.cull(walker_at(0)).pvs;
  EXPECT_TRUE(std::binary_search(pvs.begin(), pvs.end(), ObjectId{7}));  // the leaf it joined lost its stamp
  EXPECT_EQ(method.last_frame().critical, CriticalReason::none);
  // The block was never an occluder: deleting it is no critical frame.
  method.erase_object(1);
  method.set_frame(2, 0.002);
  pvs = method.cull(walker_at(0)).pvs;
  EXPECT_TRUE(std::binary_search(pvs.begin(), pvs.end(), ObjectId{7}));
  EXPECT_FALSE(std::binary_search(pvs.begin(), pvs.end(), ObjectId{1}));
  EXPECT_EQ(method.last_frame().critical, CriticalReason::none);
  // The slab was: deleting it re-marks, and building 7 has nothing in front of it any more.
  method.erase_object(0);
  EXPECT_THROW(method.erase_object(0), std::invalid_argument);
  method.set_frame(3, 0.003);
  EXPECT_EQ(method.cull(walker_at(0)).pvs, std::vector<ObjectId>{7});
  EXPECT_EQ(method.last_frame().critical, CriticalReason::occluder_deleted);
  // Put the slab back: it is sent at once, and hides building 7 from the next critical frame on.
  method.insert_object(scene.buildings[0]);
  method.set_frame(4, 0.004);
  EXPECT_EQ(method.cull(walker_at(0)).pvs, (std::vector<ObjectId>{0, 7}));
  method.set_frame(5, 100.0);
  EXPECT_EQ(method.cull(walker_at(0)).pvs, std::vector<ObjectId>{0});
  EXPECT_EQ(method.last_frame().critical, CriticalReason::expired);
}

// A path's scene timeline reaches every method and the oracle alike: the slab vanishes at frame 2
// and comes back at frame 4. The oracle sees the block only while the slab is gone, every method
// keeps it then (frustum culling and OH(OS) rebuilt on the present scene, online_is updated in
// place, its frame 2 critical), and nothing is a violation.
TEST(OnlineCulling, AScenesTimelineReachesEveryMethodAndTheOracle) {
  const Scene scene = slab_and_block();
  CameraPath path;
  for (int f = 0; f < 6; ++f) path.frames.push_back(walker_at(0.01 * f));
  path.events = {{2, {}, {0}}, {4, {0}, {}}};
  VerificationOptions options;
  options.pixels = true;
  options.measure_bare_embree = false;
  MethodOptions method_options;
  method_options.online = fine_leaves();
  const std::vector<std::string> names{"frustum", "oh_os_conservative", "online_is", "online_is_guarded"};
  const PathVerification v = verify_path(scene, SceneSource{}, path, names, method_options, options);
  ASSERT_EQ(v.checked_visible.size(), 6u);
  for (std::size_t f = 0; f < 6; ++f) {
    const bool slab_gone = f == 2 || f == 3;
    EXPECT_EQ(v.checked_visible[f], slab_gone ? std::vector<ObjectId>{1} : std::vector<ObjectId>{0}) << "frame " << f;
  }
  for (const MethodRun& run : v.runs) {
    SCOPED_TRACE(run.method);
    EXPECT_EQ(run.violation_count, 0u);
    EXPECT_EQ(run.misdrawn_total, 0u);
    EXPECT_EQ(run.pvs_size[2], 1.0);  // the block alone
    // The slab back: OH(OS) (rebuilt) hides the block at once; frustum culling never does; on-line
    // culling sends the slab at once and hides the block from its next critical frame on.
    EXPECT_EQ(run.pvs_size[4], run.method == "oh_os_conservative" ? 1.0 : 2.0);
  }
  // An outside subject cannot follow the timeline yet: a clear error, not a wrong answer.
  std::vector<MethodUnderTest> outside;
  outside.push_back({make_method("frustum", scene), nullptr, true});
  EXPECT_THROW(verify_path(scene, SceneSource{}, path, outside, method_options, options), InputError);
}

TEST(OnlineCulling, RefusesCamerasItsPlanarMaskCannotHold) {
  const Scene scene = slab_and_block();
  OnlineImageSpaceCulling method(scene, OnlineImageSpaceCulling::Variant::published);
  Camera c = walker_at(0);
  EXPECT_EQ(method.unsupported_camera(c), "");
  c.hfov = kTwoPi;
  EXPECT_NE(method.unsupported_camera(c), "");
  c = walker_at(0);
  c.projection = Projection::orthographic;
  c.ortho_width = c.ortho_height = 10;
  EXPECT_NE(method.unsupported_camera(c), "");
  OnlineCullingOptions bad;
  bad.max_speed = 0;
  EXPECT_THROW(OnlineImageSpaceCulling(scene, OnlineImageSpaceCulling::Variant::published, bad), std::invalid_argument);
}

// The pixel oracle's verdict on one method along a path: per frame, the misdrawn pixels of its
// PVS against the full scene at the camera's resolution.
struct PixelRun {
  std::vector<std::uint64_t> misdrawn;  // per frame
  std::size_t critical = 0;             // critical frames
  std::size_t deleted_occluder = 0;     // of which caused by an occluder's deletion
  std::string tree_fault;               // the first kd-tree fault after a scene event
  std::size_t culled_in_view = 0;       // frames whose PVS is smaller than frustum culling's
  std::size_t first_error = SIZE_MAX;
  std::uint64_t most = 0;
  std::size_t error_frames() const { return std::size_t(std::count_if(misdrawn.begin(), misdrawn.end(), [](auto m) { return m > 0; })); }
};
// The kd-tree after scene changes holds the present scene's polygons and nothing else: every
// live polygon in exactly one leaf, of a present object, inside its leaf's box; the root's
// count is the present scene's polygon count. Returns what is wrong ("" when nothing).
std::string kd_tree_fault(const OnlineImageSpaceCulling& method, const Scene& present) {
  const online::ScenePolygons& polygons = method.polygons();
  const auto& nodes = method.tree().nodes();
  std::vector<int> seen(polygons.size(), 0);
  for (const auto& node : nodes) {
    if (!node.leaf()) continue;
    for (std::uint32_t p : node.polygons) {
      ++seen[p];
      if (!present.find(polygons.ids[polygons.object[p]]) && !present.find_mesh(polygons.ids[polygons.object[p]]))
        return "polygon " + std::to_string(p) + " of absent object " + std::to_string(polygons.ids[polygons.object[p]]);
      const Box3& b = polygons.box[p];
      if (b.lo.x < node.box.lo.x || b.lo.y < node.box.lo.y || b.lo.z < node.box.lo.z || b.hi.x > node.box.hi.x ||
          b.hi.y > node.box.hi.y || b.hi.z > node.box.hi.z)
        return "polygon " + std::to_string(p) + " outside its leaf's box";
    }
  }
  std::size_t live = 0;
  for (std::uint32_t p = 0; p < polygons.size(); ++p) {
    if (seen[p] > 1 || (seen[p] == 1) != method.tree().alive(p)) return "polygon " + std::to_string(p) + " in " + std::to_string(seen[p]) + " leaves";
    live += seen[p];
  }
  const std::size_t expected = online::scene_polygons(present).size();
  if (live != expected || nodes[0].count != expected)
    return std::to_string(live) + " live polygons, root count " + std::to_string(nodes[0].count) + ", present scene " + std::to_string(expected);
  return "";
}

PixelRun pixel_run(const Scene& scene, const CameraPath& path, OnlineImageSpaceCulling::Variant variant, const OnlineCullingOptions& o,
                   std::size_t* tree_checks = nullptr) {
  OnlineImageSpaceCulling method(scene, variant, o);
  auto frustum = make_method("frustum", scene);
  auto truth = std::make_unique<oracle::Oracle>(scene);
  // The scene timeline, as verify_path applies it: on-line culling updated in place, frustum
  // culling and the oracle rebuilt on the present scene.
  PixelRun run;
  PresentScenes presents(scene);
  std::size_t next_event = 0;
  const auto change = [&](const std::vector<ObjectId>& appear, const std::vector<ObjectId>& vanish) {
    const Scene& present = presents.apply(appear, vanish);  // rebuilt methods and the oracle refer to it
    method.update_scene(present, appear, vanish);
    if (const std::string fault = kd_tree_fault(method, present); !fault.empty() && run.tree_fault.empty())
      run.tree_fault = "after the event at frame " + std::to_string(next_event < path.events.size() ? path.events[next_event].frame : 0) + ": " + fault;
    if (tree_checks) ++*tree_checks;
    frustum = make_method("frustum", present);
    truth = std::make_unique<oracle::Oracle>(present);
  };
  if (const std::set<ObjectId> start = absent_at_start(path); !start.empty()) change({}, std::vector<ObjectId>(start.begin(), start.end()));
  for (std::size_t f = 0; f < path.frames.size(); ++f) {
    if (next_event < path.events.size() && path.events[next_event].frame == f) {
      change(path.events[next_event].appear, path.events[next_event].vanish);
      ++next_event;
    }
    method.set_frame(f, double(f) / path.frames_per_second);
    const CullResult r = method.cull(path.frames[f]);
    run.critical += method.last_frame().critical != CriticalReason::none ? 1 : 0;
    run.deleted_occluder += method.last_frame().critical == CriticalReason::occluder_deleted ? 1 : 0;
    run.culled_in_view += r.pvs.size() < frustum->cull(path.frames[f]).pvs.size() ? 1 : 0;
    const std::uint64_t m = truth->pixels().compare(path.frames[f], r.pvs, 1).misdrawn_pixels;
    run.misdrawn.push_back(m);
    run.most = std::max(run.most, m);
    if (m > 0 && run.first_error == SIZE_MAX) run.first_error = f;
  }
  return run;
}

TEST(OnlineCullingPixels, TheDefaultWalkStaysWithinItsBudget) {
  const Scene scene = generators::default_city(1);
  generators::StreetWalkParams walk;
  walk.frames = 240;
  const CameraPath path = generators::street_walk(scene, walk, 1);
  for (const auto variant : {OnlineImageSpaceCulling::Variant::published, OnlineImageSpaceCulling::Variant::guarded}) {
    const PixelRun run = pixel_run(scene, path, variant, {});
    SCOPED_TRACE(variant == OnlineImageSpaceCulling::Variant::published ? "online_is" : "online_is_guarded");
    EXPECT_LE(run.most, OnlineCullingOptions{}.pixel_budget);
    EXPECT_EQ(run.culled_in_view, 240u);  // it culls in view at every frame...
    EXPECT_GT(run.critical, 1u);          // ...re-marking now and then,
    EXPECT_LT(run.critical, 120u);        // ...but far from every frame
  }
}

// A straw man the pixel check must catch: the published variant told the walker moves at
// 1 cm/s (it walks at 1.4 m/s) and that it may turn a radian before re-marking, so its stamps
// outlive what they hide; the first turn (from frame 1801) sweeps the view over stale marks.
// At 160 x 120 pixels, where the default budget of 200 at 320 x 240 is 50. The replay is the
// same run on the command line.
TEST(OnlineCullingPixels, AWalkerFasterThanVIsCaught) {
  const Scene scene = generators::default_city(1);
  generators::StreetWalkParams walk;
  walk.frames = 2000;  // the walk's first turn comes at frame 1801
  CameraPath path = generators::street_walk(scene, walk, 1);
  for (Camera& c : path.frames) c.width = 160, c.height = 120;
  OnlineCullingOptions o;
  o.max_speed = 0.01;
  o.critical_turn = 1.0;
  const PixelRun run = pixel_run(scene, path, OnlineImageSpaceCulling::Variant::published, o);
  std::printf("replay: cullcheck verify --generator default --seed 1 --path-params '{\"frames\":2000}' --method online_is "
              "--online-max-speed 0.01 --online-turn 1  (at 320 x 240)\n");
  EXPECT_GT(run.error_frames(), 0u);
  EXPECT_GT(run.most, 50u);
  std::printf("first error at frame %zu; %zu error frames; at most %llu pixels\n", run.first_error, run.error_frames(),
              (unsigned long long)run.most);
}

// The claim itself over generated cities and walks: the guarded variant, told the walker's
// true top speed, misdraws at most its budget at every frame. Walks are explicit moves (the
// "moves" path kind) of up to 0.1 m a frame at 30 frames a second (3 m/s) and small turns.
rc::Gen<std::vector<generators::Move>> walker_moves() {
  using generators::Move, generators::MoveKind;
  const auto step = rc::gen::map(rc::gen::pair(rc::gen::element(MoveKind::forward, MoveKind::forward, MoveKind::left, MoveKind::right, MoveKind::backward),
                                               rc::gen::inRange(0, 11)),
                                 [](const std::pair<MoveKind, int>& k) { return Move{k.first, 0.01 * k.second}; });
  const auto turn = rc::gen::map(rc::gen::inRange(-10, 11), [](int t) { return Move{MoveKind::turn, 0.005 * t}; });
  return rc::gen::container<std::vector<Move>>(60, rc::gen::weightedOneOf<Move>({{4, step}, {1, turn}}));
}

// A generated city and a 60-move walk from a street camera at 160 x 120 pixels, with the
// options the generated-walk properties use.
struct GeneratedWalk {
  generators::SceneSpec spec;
  Scene scene;
  Camera start;
  std::vector<generators::Move> moves;
  CameraPath path;
};
GeneratedWalk generated_walk() {
  GeneratedWalk w;
  w.spec = *generators::rcgen::occluded_manhattan_spec();
  w.scene = generators::scene_of(w.spec);
  w.start = *generators::rcgen::street_camera(w.scene);
  if (w.start.omnidirectional() || w.start.orthographic()) w.start = Camera{w.start.position};
  w.start.width = 160, w.start.height = 120;
  w.moves = *walker_moves();
  w.path = generators::path_of_moves(w.start, w.moves);
  return w;
}
OnlineCullingOptions generated_walk_options() {
  OnlineCullingOptions o;
  o.max_speed = 3.0;
  o.leaf_size = 4;
  o.min_distance = 5;   // the generated cities are small: occluders from 5 m
  o.pixel_budget = 50;  // at 160 x 120, a quarter of the default's 200 at 320 x 240
  return o;
}

TEST(OnlineCullingPixels, GuardedStaysWithinItsBudgetOnGeneratedWalks) {
  std::size_t cases = 0, culled = 0, remarked = 0, erring = 0;
  const PropertyOutcome outcome = run_property("OnlineCullingPixels.GuardedStaysWithinItsBudgetOnGeneratedWalks", 12, true, [&] {
    const GeneratedWalk w = generated_walk();
    const generators::SceneSpec& spec = w.spec;
    const Scene& scene = w.scene;
    const Camera& start = w.start;
    const auto& moves = w.moves;
    const CameraPath& path = w.path;
    const OnlineCullingOptions o = generated_walk_options();
    const PixelRun run = pixel_run(scene, path, OnlineImageSpaceCulling::Variant::guarded, o);
    ++cases;
    culled += run.culled_in_view > 0 ? 1 : 0;
    remarked += run.critical > 1 ? 1 : 0;
    erring += run.error_frames() > 0 ? 1 : 0;
    RC_LOG() << "replay: cullcheck verify " << generators::replay_args(spec) << " --path-kind moves --path-params '"
             << generators::moves_params(start, moves).dump()
             << "' --method online_is_guarded --online-max-speed 3 --online-leaf-size 4 --online-min-distance 5 --online-pixel-budget 50\n";
    RC_ASSERT(run.most <= o.pixel_budget);
  });
  EXPECT_TRUE(outcome.held);
  std::printf("%zu walks: %zu culled in view, %zu re-marked after the first frame, %zu misdrew a pixel (within budget)\n", cases, culled,
              remarked, erring);
  EXPECT_GE(2 * culled, cases) << "walks where occlusion culling did work";
  EXPECT_GE(4 * remarked, cases) << "walks that reached a second critical frame";
}

// Section 6 over generated cities, walks and scene timelines (buildings vanishing and coming
// back every few frames): after every event the kd-tree holds exactly the present polygons, and
// the guarded variant, updated in place, stays within its pixel budget against the oracle of
// the present scene. Counts that the hard case came: an occluder deleted under a stamp.
TEST(OnlineCullingPixels, GuardedStaysWithinItsBudgetWhileTheSceneChanges) {
  std::size_t cases = 0, events = 0, checks = 0, occluder_deleted = 0, erring = 0;
  const PropertyOutcome outcome = run_property("OnlineCullingPixels.GuardedStaysWithinItsBudgetWhileTheSceneChanges", 12, true, [&] {
    GeneratedWalk w = generated_walk();
    const generators::SceneSpec& spec = w.spec;
    const Scene& scene = w.scene;
    const Camera& start = w.start;
    const auto& moves = w.moves;
    CameraPath& path = w.path;
    generators::TimelineParams t;
    t.every = *rc::gen::inRange(2, 16);
    t.churn = 0.05 * *rc::gen::inRange(1, 7);
    t.late = 0.05 * *rc::gen::inRange(0, 5);
    const std::uint64_t seed = *rc::gen::inRange<std::uint64_t>(0, 1000);
    path.events = generators::scene_timeline(scene, path.frames.size(), t, seed);
    const OnlineCullingOptions o = generated_walk_options();
    nlohmann::json params = generators::moves_params(start, moves);
    params["timeline"] = {{"every", t.every}, {"churn", t.churn}, {"late", t.late}};
    RC_LOG() << "replay: cullcheck verify " << generators::replay_args(spec) << " --path-kind moves --path-seed " << seed
             << " --path-params '" << params.dump()
             << "' --method online_is_guarded --online-max-speed 3 --online-leaf-size 4 --online-min-distance 5 --online-pixel-budget 50\n";
    std::size_t tree_checks = 0;
    const PixelRun run = pixel_run(scene, path, OnlineImageSpaceCulling::Variant::guarded, o, &tree_checks);
    ++cases;
    events += path.events.size();
    checks += tree_checks;
    occluder_deleted += run.deleted_occluder > 0 ? 1 : 0;
    erring += run.error_frames() > 0 ? 1 : 0;
    RC_ASSERT(run.tree_fault == "");
    RC_ASSERT(run.most <= o.pixel_budget);
  });
  EXPECT_TRUE(outcome.held);
  std::printf("%zu walks, %zu scene events, %zu kd-tree checks; %zu walks re-marked because an occluder was deleted; %zu misdrew a pixel\n",
              cases, events, checks, occluder_deleted, erring);
  EXPECT_GE(checks, events);
  EXPECT_GE(2 * occluder_deleted, cases) << "walks where a deleted occluder forced a critical frame";
}

// The kd-tree check above must be able to fire: a tree not told of a deletion still holds the
// vanished building's polygons, and an updated tree no longer matches the full scene.
TEST(OnlineCulling, TheKdTreeCheckCatchesATreeThatMissedAnEvent) {
  const Scene scene = generators::default_city(1);
  OnlineImageSpaceCulling method(scene, OnlineImageSpaceCulling::Variant::published);
  EXPECT_EQ(kd_tree_fault(method, scene), "");
  const ObjectId gone = scene.buildings[3].id;
  const Scene present = present_scene(scene, {gone});
  EXPECT_NE(kd_tree_fault(method, present).find("of absent object " + std::to_string(gone)), std::string::npos);
  ASSERT_TRUE(method.update_scene(present, {}, {gone}));
  EXPECT_EQ(kd_tree_fault(method, present), "");
  EXPECT_NE(kd_tree_fault(method, scene).find("present scene"), std::string::npos);
}

// The claims ledger's counterexamples (reports/online_claims.cpp), kept: a critical frame at the
// start camera, one sideways step inside δ, and the oracle at frame 1.
struct StepCase {
  std::string generator;
  std::uint64_t seed;
  const char* params;
  const char* path;
};
std::vector<ObjectId> missed_after_step(const StepCase& c, OnlineImageSpaceCulling::Variant variant, const OnlineCullingOptions& o) {
  const Scene scene = generators::make_city(c.generator, c.seed, nlohmann::json::parse(c.params));
  const CameraPath path = generators::moves_path(nlohmann::json::parse(c.path));
  OnlineImageSpaceCulling method(scene, variant, o);
  method.set_frame(0, 0.0);
  method.cull(path.frames[0]);
  method.set_frame(1, 1.0 / 30);
  const std::vector<ObjectId> pvs = method.cull(path.frames[1]).pvs;
  const oracle::Oracle truth(scene);
  oracle::OracleAnswer seen = truth.visible_set(path.frames[1], {});
  std::vector<ObjectId> missed;
  std::set_difference(seen.visible.begin(), seen.visible.end(), pvs.begin(), pvs.end(), std::back_inserter(missed));
  std::erase_if(missed, [&](ObjectId id) { return seen.sampling && !truth.confirm_witness(seen, id, path.frames[1]).stands(); });
  return missed;
}
OnlineCullingOptions single_occluder() {
  OnlineCullingOptions o;
  o.occluders = 1, o.leaf_size = 1, o.min_distance = 5, o.max_speed = 0.001, o.ground_occluder = false;
  return o;
}

// Eq. (1) as printed gives δ = 2ΔD / (s tan(θ/2)): at a 30-degree field of view that is
// 1 / tan^2(15 deg) = 13.9 times what Δ pixels subtend at the centre, and a step of 2.02 m past
// one wall shows building 23. The corrected δ is far smaller, so the same start re-marks first.
TEST(OnlineClaims, EquationOneAsPrintedIsRefutedByASidewaysStep) {
  const StepCase c{"manhattan", 1001,
                   R"({"block_size":30,"blocks_x":4,"blocks_y":4,"buildings_per_block":4,"street_width":14,"thin_fraction":0.3})",
                   R"({"moves":[["left",2.019899284411473]],"start":{"far":100000.0,"hfov":0.5235987755982988,"near":0.1,"pitch":0.0,"position":[-49.282287699302415,-12.97727666702825,1.7],"roll":0.0,"vfov":0.39269908169872414,"yaw":0.15128485741179362}})"};
  EXPECT_EQ(missed_after_step(c, OnlineImageSpaceCulling::Variant::published, single_occluder()), std::vector<ObjectId>{23});
  EXPECT_EQ(missed_after_step(c, OnlineImageSpaceCulling::Variant::guarded, single_occluder()), std::vector<ObjectId>{});
}

// Fig. 5's leak: with its whole occluder set, the guarded variant (corrected δ, the step 0.065 m
// well inside it) still hides building 0 behind the eroded union of two occluders' images.
TEST(OnlineClaims, ShrinkingTheUnionLeaksAsFigureFiveWarns) {
  const StepCase c{"manhattan", 1000,
                   R"({"block_size":20,"blocks_x":5,"blocks_y":4,"buildings_per_block":4,"street_width":12,"thin_fraction":0.3})",
                   R"({"moves":[["left",0.06522977817210512]],"start":{"far":100000.0,"hfov":1.5707963267948966,"near":0.1,"pitch":0.0,"position":[47.22131958651423,-46.7123184302231,1.7],"roll":0.0,"vfov":1.1780972450961724,"yaw":2.964030868372489}})"};
  OnlineCullingOptions o;
  o.leaf_size = 1, o.min_distance = 5, o.max_speed = 0.001;
  const std::vector<ObjectId> missed = missed_after_step(c, OnlineImageSpaceCulling::Variant::guarded, o);
  EXPECT_TRUE(std::find(missed.begin(), missed.end(), ObjectId{0}) != missed.end());
}

}  // namespace
}  // namespace cullcheck
