// Mesh scenes (walls with doors and windows, arcades, bridges: generators/openings_city.cpp) and
// orthographic cameras, the cases 2.5D prisms cannot express: frustum culling, the one engine
// method that runs on them, is held to the oracle over the fuzzer's camera paths; the glTF a
// subject loads gives the oracle the same visible sets as the scene it came from; and 2.5D
// methods are refused with a reason. The properties count that they reached the hard cases:
// objects witnessed through a wall's bounding box (through an opening or under an arcade), and
// orthographic cameras.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <algorithm>
#include <cstdio>
#include <iterator>

#include "core/formats/mesh_formats.hpp"
#include "engine/method.hpp"
#include "generators/fuzz_cases.hpp"
#include "oracle/oracle.hpp"
#include "properties/property_oracle.hpp"

namespace cullcheck {
namespace {

namespace rcgen = generators::rcgen;

// Whether the segment a-b crosses the box (slab test).
bool segment_crosses(Vec3 a, Vec3 b, const Box3& box) {
  double t0 = 0.0, t1 = 1.0;
  const double from[3] = {a.x, a.y, a.z}, to[3] = {b.x, b.y, b.z}, lo[3] = {box.lo.x, box.lo.y, box.lo.z},
               hi[3] = {box.hi.x, box.hi.y, box.hi.z};
  for (int k = 0; k < 3; ++k) {
    const double d = to[k] - from[k];
    if (d == 0.0) {
      if (from[k] < lo[k] || from[k] > hi[k]) return false;
      continue;
    }
    double u = (lo[k] - from[k]) / d, v = (hi[k] - from[k]) / d;
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}

TEST(MeshScenes, FrustumCullingIsConservativeOnScenesWithOpenings) {
  int through_openings = 0, orthographic = 0, cases = 0;
  const bool held = rc::check("frustum culling on openings scenes", [&] {
    const generators::FuzzCase c = *rcgen::fuzz_case(rcgen::openings_spec(), /*orthographic=*/true);
    const Scene scene = generators::scene_of(c.spec);
    RC_PRE(!scene.prisms_only());  // every frontage drawn plain: no mesh object
    const auto method = make_method("frustum", scene);
    const oracle::Oracle truth(scene);
    ++cases;
    for (const Camera& camera : c.path.frames) {
      orthographic += camera.orthographic();
      const oracle::OracleAnswer seen = truth.visible_set(camera, property_oracle());
      const CullResult culled = method->cull(camera);
      std::vector<ObjectId> missed;
      std::set_difference(seen.visible.begin(), seen.visible.end(), culled.pvs.begin(), culled.pvs.end(), std::back_inserter(missed));
      if (!missed.empty()) {
        std::string cam = camera_to_json_text(camera);
        cam.pop_back();
        RC_LOG() << "replay: cullcheck verify " << generators::replay_args(c.spec) << " --method frustum --camera '" << cam << "'\n";
      }
      RC_ASSERT(missed.empty());
      // The hard case: a witness ray that crossed a wall mesh's box before its hit (so it went
      // through an opening, or under the slab of an arcade).
      if (!seen.sampling) continue;
      for (const auto& [id, ray] : seen.sampling->witnesses)
        for (const MeshObject& m : scene.meshes)
          if (m.id != id && segment_crosses(ray.origin, ray.origin + ray.direction * (ray.t_hit * 0.999), m.bounds)) {
            ++through_openings;
            break;
          }
    }
  });
  std::printf("%d cases: %d objects witnessed through a wall's box, %d orthographic frames\n", cases, through_openings, orthographic);
  EXPECT_TRUE(held);
  EXPECT_GT(through_openings, 50) << "the property did not reach objects seen through openings";
  EXPECT_GT(orthographic, 5) << "the property did not reach orthographic cameras";
}

// The glTF handed to a subject is the scene the oracle judges: same visible sets, camera by camera.
TEST(MeshScenes, TheGlbGivesTheOracleTheSameVisibleSets) {
  const Scene scene = generators::make_city("openings", 3, {{"blocks_x", 2}, {"blocks_y", 1}});
  const std::string path = testing::TempDir() + "/openings.glb";
  formats::write_glb(scene, path);
  const Scene loaded = formats::read_gltf(path);
  ASSERT_EQ(loaded.ids(), scene.ids());
  const oracle::Oracle a(scene), b(loaded);
  int compared = 0, seen = 0;
  rc::check("the .glb's visible sets", [&] {
    const Camera camera = *rcgen::camera_in(scene);
    const auto va = a.visible_set(camera, property_oracle()).visible, vb = b.visible_set(camera, property_oracle()).visible;
    // float32 vertices move by at most half a unit in the last place: rays aimed at an edge may
    // see a sliver differently, so the sets may differ by objects seen edge-on only.
    std::vector<ObjectId> only_a, only_b;
    std::set_difference(va.begin(), va.end(), vb.begin(), vb.end(), std::back_inserter(only_a));
    std::set_difference(vb.begin(), vb.end(), va.begin(), va.end(), std::back_inserter(only_b));
    ++compared;
    seen += static_cast<int>(va.size());
    RC_ASSERT(only_a.size() + only_b.size() <= 1u);
  });
  EXPECT_GT(seen, compared) << "the cameras saw almost nothing";
}

TEST(MeshScenes, TwoAndAHalfDMethodsSayWhyTheyDoNotRun) {
  const Scene scene = generators::make_city("openings", 1, {{"blocks_x", 1}, {"blocks_y", 1}});
  ASSERT_FALSE(scene.meshes.empty());
  EXPECT_EQ(method_unavailable_reason("frustum", scene), "");
  const std::string why = method_unavailable_reason("oh_os_conservative", scene);
  EXPECT_NE(why.find("mesh object"), std::string::npos) << why;
  EXPECT_THROW(make_method("oh_os_conservative", scene), std::invalid_argument);
  EXPECT_THROW(make_region_method("shrink_former", scene), std::invalid_argument);
}

}  // namespace
}  // namespace cullcheck
