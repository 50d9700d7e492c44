// Pinned outputs of the seeded generators: literal numbers recorded once, never a run compared
// with itself. Every stored replay (a report's replay_flags, the claims ledger's counterexamples,
// the kept regression cases, RC_PARAMS reproduce lines, the README's figures) names a generator,
// a seed and parameters and trusts them to rebuild the same scene and path. A change of the PRNG,
// of a distribution or of a generator's layout silently breaks all of them; these pins make it a
// loud failure instead.
//
// What is pinned: the first outputs of the PRNG, and a 64-bit FNV-1a digest of the canonical
// JSON text (scene_to_json_text, path_to_json_text: byte-identical for the same scene) of a few
// scenes of every generator in city_registry.cpp and a few paths of every kind in
// camera_path_registry.cpp, with a few literal coordinates so that a failure also shows what
// moved. The digests are the same in the RelWithDebInfo and Debug builds (checked when they were
// recorded): the generators snap to a 1 mm grid and the build uses -ffp-contract=off.
//
// If a pin fails on purpose (a deliberate change of a generator), update it and say in the commit
// that every stored replay of that generator is invalid from then on.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene_io.hpp"
#include "generators/camera_moves.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {
namespace {

using nlohmann::json;

// FNV-1a, 64-bit (Fowler, Noll, Vo): byte order only, so the same text hashes the same anywhere.
std::uint64_t fnv1a64(const std::string& bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

std::string hex(std::uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%016" PRIx64, v);
  return buf;
}

// A double at full precision (round-trips), so a pin is the exact number, not a rounding of it.
std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

const char* const kInvalidated =
    "\n  The generator's output changed: every stored replay of it (report.json replay_flags, claims-ledger "
    "counterexamples, kept regression cases, RC_PARAMS reproduce lines, README figures) no longer rebuilds the "
    "scene it recorded. If the change is deliberate, update this pin and say so in the commit.";

TEST(PinnedStreams, PrngOutputs) {
  Random r(12345);
  EXPECT_EQ(hex(r.next_u64()), "0xbe6a36374160d49b") << kInvalidated;
  EXPECT_EQ(hex(r.next_u64()), "0x214aaa0637a688c6") << kInvalidated;
  EXPECT_EQ(hex(r.next_u64()), "0xf69d16de9954d388") << kInvalidated;
  Random s = Random::stream(7, 1, 2, 3);
  EXPECT_EQ(hex(s.next_u64()), "0x4e8c3526284b01f0") << kInvalidated;
  // The hand-written distributions over that engine.
  Random d(1);
  EXPECT_EQ(exact(d.uniform01()), "0.70292183315885048") << kInvalidated;
  EXPECT_EQ(exact(d.uniform_real(-3.0, 5.0)), "1.1634929595108554") << kInvalidated;
  EXPECT_EQ(d.uniform_int(-2, 7), -2) << kInvalidated;
  EXPECT_EQ(d.bernoulli(0.5), true) << kInvalidated;
}

struct PinnedScene {
  const char* generator;
  std::uint64_t seed;
  const char* params;
  std::size_t objects;  // buildings + mesh objects
  const char* digest;
};

// At least two scenes of every generator; the default city with seed 1 is the CLI's default.
const std::vector<PinnedScene>& pinned_scenes() {
  static const std::vector<PinnedScene> pins = {
      {"default", 1, "{}", 2808, "0x120ff29b7c4ffc1a"},
      {"default", 7, "{}", 2808, "0xaa4c2883eecb49d2"},
      {"manhattan", 0, R"({"blocks_x":3,"blocks_y":2,"buildings_per_block":5,"thin_fraction":0.4})", 30, "0x0086ad737f9f31a7"},
      {"manhattan", 42, R"({"blocks_x":4,"blocks_y":4,"tower_fraction":0.3})", 96, "0x7e69f72d7048ebb5"},
      {"plaza", 1, R"({"blocks_x":4,"blocks_y":4})", 78, "0x9cf65bb9d5db4241"},
      {"plaza", 9, "{}", 366, "0xc2cf823183a35f31"},
      {"scatter", 1, R"({"count":120,"area_size":400})", 120, "0xd7d7a5490ae00e24"},
      {"scatter", 2024, "{}", 399, "0xd93d2a0b4169f19b"},
      {"irregular", 5, R"({"count":200})", 200, "0x6a1400e14e08d642"},
      {"irregular", 77, R"({"count":100,"area_size":500})", 98, "0xd2befd61e66fcd9c"},
      {"thesis", 1, R"({"grid_x":20,"grid_y":20})", 400, "0xd2d95b0fd404e91c"},
      {"thesis", 3, R"({"grid_x":40,"grid_y":24})", 960, "0xd509fcf232878028"},
      {"openings", 5, "{}", 139, "0xdf2f1cfe1c592fbf"},
      {"openings", 2, R"({"blocks_x":2,"blocks_y":1})", 29, "0x87b4c4e2cb675001"},
      {"kept", 0, R"({"case":"low_planter"})", 2, "0x0ed60efec5cde803"},
      {"kept", 0, R"({"case":"slab_across_the_disc"})", 2, "0x210fbe7974572ca5"},
      {"slot_city", 1, "{}", 11, "0x58f7766151964bc8"},
      {"slot_city", 7, R"({"slots_x":5,"slots_y":3})", 10, "0x4348700a903f7d23"},
      {"star_block_city", 1, R"({"count":20})", 20, "0xa753f6cc1a4b97d9"},
      {"star_block_city", 2, R"({"count":12,"vertices":9})", 12, "0x561c2d2b5b4d3719"},
      {"detailed", 1, R"({"blocks_x":2,"blocks_y":2,"buildings_per_block":2})", 8, "0x24c5984e448c3d63"},
      {"detailed", 4, R"({"blocks_x":3,"blocks_y":1,"tower_fraction":0.5,"max_height":60})", 18, "0xf77973cc74fbe890"},
  };
  return pins;
}

std::string replay_of(const PinnedScene& p) {
  return "--generator " + std::string(p.generator) + " --seed " + std::to_string(p.seed) + " --params '" + p.params + "'";
}

TEST(PinnedStreams, EveryCityGeneratorIsPinned) {
  for (const std::string& name : city_generator_names()) {
    int pins = 0;
    for (const PinnedScene& p : pinned_scenes()) pins += name == p.generator;
    EXPECT_GE(pins, 2) << "generator '" << name << "' has no pinned digests in " << __FILE__;
  }
}

TEST(PinnedStreams, SceneDigests) {
  for (const PinnedScene& p : pinned_scenes()) {
    const Scene scene = make_city(p.generator, p.seed, json::parse(p.params));
    const std::string text = scene_to_json_text(scene);
    EXPECT_EQ(scene.buildings.size() + scene.meshes.size(), p.objects) << replay_of(p) << kInvalidated;
    EXPECT_EQ(hex(fnv1a64(text)), p.digest) << "scene " << replay_of(p) << " (" << text.size() << " bytes of JSON)"
                                            << kInvalidated;
  }
}

struct PinnedPath {
  const char* kind;
  const char* generator;  // the scene it runs in
  std::uint64_t scene_seed;
  const char* scene_params;
  std::uint64_t seed;
  const char* params;
  std::size_t frames;
  const char* digest;
};

// At least two paths of every kind; the first is the main job's default walk (ci/setup.sh).
const std::vector<PinnedPath>& pinned_paths() {
  static const std::vector<PinnedPath> pins = {
      {"street_walk", "default", 1, "{}", 1, R"({"frames":300})", 300, "0xce3a3d240d2f35ea"},
      {"street_walk", "manhattan", 3, R"({"blocks_x":4,"blocks_y":3,"block_size":30,"street_width":12})", 11,
       R"({"frames":2000,"hfov_deg":360})", 2000, "0x2f4a7128c303842a"},
      {"street_walk", "thesis", 2, R"({"grid_x":20,"grid_y":15})", 4, R"({"frames":600})", 600, "0x91eaca1bf342477d"},
      // Scenes without a grid: the walk through free-space cells (free_space_walk.cpp).
      {"street_walk", "irregular", 5, R"({"count":150})", 7, R"({"frames":600})", 600, "0xb3783733918f72c8"},
      {"street_walk", "scatter", 2, R"({"count":150})", 7, R"({"frames":600})", 600, "0x228c96d6199a37bb"},
      {"fly_through", "default", 4, "{}", 8, R"({"frames":600,"dip_fraction":0.5})", 600, "0xb5fec2f2499b1eb2"},
      {"fly_through", "irregular", 4, R"({"count":150})", 2, R"({"frames":400})", 400, "0xfa2d32f934990957"},
      {"plaza_crossing", "plaza", 1,
       R"({"blocks_x":11,"blocks_y":10,"block_size":40,"street_width":10,"buildings_per_block":4,"plaza_blocks_x":3,"plaza_blocks_y":2,"kiosk_count":0})",
       0, "{}", 310, "0x6ebc552b3d41ed07"},
      {"plaza_crossing", "default", 1, "{}", 0, R"({"step_m":1.5,"turn_step_deg":5})", 851, "0x423abb34cc3e3929"},
      {"moves", "manhattan", 0, "{}", 0,
       R"({"start":{"position":[45.4357664,39.568818,1.5],"yaw":4.71238898038469,"hfov":0.5235987755982988},"moves":[["left",5.0],["turn",-0.3],["forward",2.5],["rise",1.0],["stop"]]})",
       6, "0x6aaab65205c17c8a"},
      {"moves", "manhattan", 0, "{}", 0,
       R"({"start":{"position":[0,0,1.7]},"moves":[["backward",3.0],["right",0.05],["turn",6.5]]})", 4,
       "0xbb33ed7e57a5f259"},
  };
  return pins;
}

std::string replay_of(const PinnedPath& p) {
  return "--generator " + std::string(p.generator) + " --seed " + std::to_string(p.scene_seed) + " --params '" +
         p.scene_params + "' --path-kind " + p.kind + " --path-seed " + std::to_string(p.seed) + " --path-params '" +
         p.params + "'";
}

TEST(PinnedStreams, EveryCameraPathKindIsPinned) {
  for (const std::string& kind : camera_path_kinds()) {
    int pins = 0;
    for (const PinnedPath& p : pinned_paths()) pins += kind == p.kind;
    EXPECT_GE(pins, 2) << "camera path kind '" << kind << "' has no pinned digests in " << __FILE__;
  }
}

TEST(PinnedStreams, CameraPathDigests) {
  for (const PinnedPath& p : pinned_paths()) {
    const Scene scene = make_city(p.generator, p.scene_seed, json::parse(p.scene_params));
    const CameraPath path = make_camera_path(p.kind, scene, p.seed, json::parse(p.params));
    const std::string text = path_to_json_text(path);
    EXPECT_EQ(path.frames.size(), p.frames) << replay_of(p) << kInvalidated;
    EXPECT_EQ(hex(fnv1a64(text)), p.digest) << "path " << replay_of(p) << " (" << text.size() << " bytes of JSON)"
                                            << kInvalidated;
  }
}

// A few literal coordinates, so that a failing digest comes with a picture of what moved: the
// first building of the CLI's default city, and the default walk's first and last eyes.
TEST(PinnedStreams, LiteralCoordinatesOfTheDefaultCityAndWalk) {
  const Scene scene = make_city("default", 1, json::object());
  ASSERT_FALSE(scene.buildings.empty());
  const Building& first = scene.buildings.front();
  EXPECT_EQ(exact(first.height), "24.984999999999999") << kInvalidated;
  ASSERT_EQ(first.footprint.size(), 4u) << kInvalidated;
  EXPECT_EQ(exact(first.footprint[0].x), "-563.697") << kInvalidated;
  EXPECT_EQ(exact(first.footprint[0].y), "-566.76199999999994") << kInvalidated;
  EXPECT_EQ(exact(first.footprint[2].x), "-553.02099999999996") << kInvalidated;
  EXPECT_EQ(exact(first.footprint[2].y), "-549.50599999999997") << kInvalidated;
  const Building& last = scene.buildings.back();
  EXPECT_EQ(exact(last.height), "1.486") << kInvalidated;
  EXPECT_EQ(exact(last.footprint[0].x), "35.982999999999997") << kInvalidated;
  EXPECT_EQ(exact(last.footprint[0].y), "14.305999999999999") << kInvalidated;
  const CameraPath walk = make_camera_path("street_walk", scene, 1, {{"frames", 300}});
  ASSERT_EQ(walk.frames.size(), 300u);
  EXPECT_EQ(exact(walk.frames.front().position.x), "-96") << kInvalidated;
  EXPECT_EQ(exact(walk.frames.front().position.y), "498.08290630876485") << kInvalidated;
  EXPECT_EQ(exact(walk.frames.front().yaw), "4.7123889803846897") << kInvalidated;
  EXPECT_EQ(exact(walk.frames.back().position.x), "-94.721506172839497") << kInvalidated;
  EXPECT_EQ(exact(walk.frames.back().position.y), "487.46118411459253") << kInvalidated;
  EXPECT_EQ(exact(walk.frames.back().yaw), "4.7123889803846897") << kInvalidated;
}

}  // namespace
}  // namespace cullcheck::generators
