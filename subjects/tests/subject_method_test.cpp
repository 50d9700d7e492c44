// SubjectMethod (subjects/subject_method.hpp) against a scripted subject
// (subjects/tests/scripted_subject.py): the handshake, frames answered, and each way a subject
// fails raising SubjectError with its kind and frame.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "core/elapsed.hpp"
#include "core/scene_io.hpp"
#include "subjects/tests/subject_error_of.hpp"
#include "subjects/subject_method.hpp"

#ifndef CULLCHECK_SCRIPTED_SUBJECT
#error "CULLCHECK_SCRIPTED_SUBJECT must name subjects/tests/scripted_subject.py"
#endif

namespace cullcheck {
namespace {

using Kind = SubjectError::Kind;
using test_support::error_of;
using Clock = std::chrono::steady_clock;

// Buildings 1 and 3 and mesh 5: three objects, ids sorted [1, 3, 5].
Scene three_objects() {
  Scene s;
  s.buildings.push_back(box_building(3, 20, 0, 30, 10, 5));
  s.buildings.push_back(box_building(1, 0, 0, 10, 10, 5));
  MeshObject m;
  m.id = 5;
  m.vertices = {{40, 0, 0}, {41, 0, 0}, {40, 1, 0}, {40, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  validate_and_finish(m);
  s.meshes.push_back(m);
  return s;
}

SubjectOptions scripted(const std::string& mode, int at = 0, const std::string& bye_file = "") {
  SubjectOptions o;
  o.command = std::string("python3 ") + CULLCHECK_SCRIPTED_SUBJECT + " " + mode + " " + std::to_string(at) +
              (bye_file.empty() ? "" : " " + bye_file);
  o.files = {"", "/nonexistent/scene.json"};  // the scripted subject loads no file
  o.hello_timeout = 20;
  o.frame_timeout = 20;
  o.exit_timeout = 5;
  return o;
}

Camera camera() {
  Camera c;
  c.position = {5, -20, 2};
  c.yaw = kPi / 2;
  return c;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(SubjectMethod, HandshakeTakesTheNameAndClaimFromReady) {
  const Scene scene = three_objects();
  SubjectMethod m(scene, scripted("good"), 4);
  // The ready's name is built from the hello: 3 objects, 4 frames.
  EXPECT_EQ(m.name(), "subject:scripted-3-objects-4-frames");
  EXPECT_EQ(m.ready().name, "scripted-3-objects-4-frames");
  EXPECT_TRUE(m.claims_conservative());
  EXPECT_FALSE(m.pixel_error_budget().has_value());
  // It listed "perspective" only.
  EXPECT_EQ(m.unsupported_camera(camera()), "");
  Camera ortho = camera();
  ortho.projection = Projection::orthographic;
  ortho.ortho_width = ortho.ortho_height = 10;
  EXPECT_TRUE(contains(m.unsupported_camera(ortho), "orthographic camera")) << m.unsupported_camera(ortho);
  Camera omni = camera();
  omni.hfov = kTwoPi;
  EXPECT_TRUE(contains(m.unsupported_camera(omni), "omnidirectional camera")) << m.unsupported_camera(omni);
  EXPECT_GT(m.timing().hello_ms, 0.0);
}

TEST(SubjectMethod, GivenNameAndApproximateClaim) {
  const Scene scene = three_objects();
  SubjectOptions o = scripted("approximate");
  o.name = "mine";
  SubjectMethod m(scene, o, 1);
  EXPECT_EQ(m.name(), "subject:mine");
  EXPECT_FALSE(m.claims_conservative());
  EXPECT_EQ(m.pixel_error_budget(), std::optional<std::uint64_t>(7));
}

TEST(SubjectMethod, FramesAreAnsweredWithTheSubjectsTiming) {
  const Scene scene = three_objects();
  const std::string bye = ::testing::TempDir() + "subject_method_bye.txt";
  std::remove(bye.c_str());
  {
    SubjectMethod m(scene, scripted("good", 0, bye), 3);
    // Frame f is answered with the first f + 1 ids and cull_ms = time * 1000.
    m.set_frame(0, 0.001);
    CullResult r = m.cull(camera());
    EXPECT_EQ(r.pvs, (std::vector<ObjectId>{1}));
    EXPECT_DOUBLE_EQ(r.stats.cull_ms, 1.0);
    EXPECT_GE(r.stats.protocol_ms, 0.0);
    m.set_frame(2, 0.002);
    r = m.cull(camera());
    EXPECT_EQ(r.pvs, (std::vector<ObjectId>{1, 3, 5}));
    EXPECT_DOUBLE_EQ(r.stats.cull_ms, 2.0);
    EXPECT_EQ(m.timing().frames, 2u);
    EXPECT_DOUBLE_EQ(m.timing().subject_cull_ms, 3.0);
    EXPECT_EQ(m.timing().frames_without_timing, 0u);
    EXPECT_GE(m.timing().round_trip_ms, m.timing().protocol_ms);
  }  // the destructor says bye; the subject writes the file and exits
  std::ifstream in(bye);
  std::string said;
  std::getline(in, said);
  EXPECT_EQ(said, "bye");
  std::remove(bye.c_str());
}

TEST(SubjectMethod, WithoutCullMsTheRoundTripIsTheTime) {
  const Scene scene = three_objects();
  SubjectMethod m(scene, scripted("no-timing"), 1);
  m.set_frame(0, 5.0);  // would be cull_ms 5000 if it were sent
  const CullResult r = m.cull(camera());
  EXPECT_EQ(r.pvs, (std::vector<ObjectId>{1}));
  EXPECT_EQ(r.stats.cull_ms, r.stats.protocol_ms);  // the measured round trip, not a sent cull_ms
  EXPECT_EQ(m.timing().frames_without_timing, 1u);
}

TEST(SubjectMethod, CrashIsAnErrorAtItsFrame) {
  const Scene scene = three_objects();
  SubjectOptions o = scripted("crash", 1);
  o.stderr_path = ::testing::TempDir() + "subject_method_crash_stderr.txt";
  SubjectMethod m(scene, o, 3);
  m.set_frame(0, 0);
  EXPECT_EQ(m.cull(camera()).pvs, (std::vector<ObjectId>{1}));
  m.set_frame(1, 0);
  const SubjectError e = error_of([&] { (void)m.cull(camera()); });
  EXPECT_EQ(e.kind(), Kind::crashed) << e.what();
  EXPECT_EQ(e.frame(), 1);
  EXPECT_EQ(e.subject(), "subject 'scripted-3-objects-3-frames'");
  EXPECT_TRUE(contains(e.what(), "subject 'scripted-3-objects-3-frames' at frame 1: crashed: ")) << e.what();
  EXPECT_TRUE(contains(e.what(), "(exited with status 3)")) << e.what();
  EXPECT_TRUE(contains(e.what(), "its stderr ends: scripted subject: crashing at frame 1")) << e.what();
  std::remove(o.stderr_path.c_str());
}

TEST(SubjectMethod, HangIsATimeoutAtItsFrame) {
  const Scene scene = three_objects();
  SubjectOptions o = scripted("hang", 0);
  o.frame_timeout = 0.3;
  {
    SubjectMethod m(scene, o, 1);
    m.set_frame(0, 0);
    const auto asked = Clock::now();
    const SubjectError e = error_of([&] { (void)m.cull(camera()); });
    EXPECT_GE(seconds_since(asked), 0.29);  // not early; late would be the hour the subject sleeps
    EXPECT_EQ(e.kind(), Kind::timed_out) << e.what();
    EXPECT_EQ(e.frame(), 0);
    EXPECT_TRUE(contains(e.what(), "at frame 0: timed out: no answer within 0.3 s (awaiting the visible ids)")) << e.what();
  }  // the hour-long sleep is killed, not waited for (else this test hangs until CTest's timeout)
}

TEST(SubjectMethod, LiesAreErrorsAtTheirFrame) {
  const Scene scene = three_objects();
  {
    SubjectMethod m(scene, scripted("wrong-frame", 1), 3);
    m.set_frame(0, 0);
    (void)m.cull(camera());
    m.set_frame(1, 0);
    const SubjectError e = error_of([&] { (void)m.cull(camera()); });
    EXPECT_EQ(e.kind(), Kind::wrong_frame) << e.what();
    EXPECT_EQ(e.frame(), 1);
    EXPECT_TRUE(contains(e.what(), "at frame 1: wrong frame: answered frame 2, expected 1")) << e.what();
  }
  {
    SubjectMethod m(scene, scripted("unknown-id", 0), 1);
    m.set_frame(0, 0);
    const SubjectError e = error_of([&] { (void)m.cull(camera()); });
    EXPECT_EQ(e.kind(), Kind::unknown_id) << e.what();
    EXPECT_EQ(e.frame(), 0);
    EXPECT_TRUE(contains(e.what(), "object 99999 is not in the scene")) << e.what();
  }
}

TEST(SubjectMethod, HandshakeFailures) {
  const Scene scene = three_objects();
  const SubjectError garbage = error_of([&] { SubjectMethod m(scene, scripted("garbage-ready"), 1); });
  EXPECT_EQ(garbage.kind(), Kind::garbage) << garbage.what();
  EXPECT_EQ(garbage.frame(), SubjectError::kHandshake);
  // Before a ready, the subject is named after the script.
  EXPECT_TRUE(contains(garbage.what(), "subject 'scripted_subject.py' during the handshake: garbage: ")) << garbage.what();

  const SubjectError version = error_of([&] { SubjectMethod m(scene, scripted("version-2"), 1); });
  EXPECT_EQ(version.kind(), Kind::protocol) << version.what();
  EXPECT_EQ(version.frame(), SubjectError::kHandshake);
  EXPECT_TRUE(contains(version.what(), "speaks protocol 2")) << version.what();

  SubjectOptions silent = scripted("silent");
  silent.hello_timeout = 0.3;
  const auto start = Clock::now();
  const SubjectError timeout = error_of([&] { SubjectMethod m(scene, silent, 1); });
  EXPECT_GE(seconds_since(start), 0.29);
  EXPECT_EQ(timeout.kind(), Kind::timed_out) << timeout.what();
  EXPECT_EQ(timeout.frame(), SubjectError::kHandshake);
  EXPECT_TRUE(contains(timeout.what(), "(awaiting its ready message)")) << timeout.what();

  SubjectOptions missing;
  missing.command = "/nonexistent/cullcheck-subject 2>/dev/null";
  const SubjectError absent = error_of([&] { SubjectMethod m(scene, missing, 1); });
  EXPECT_EQ(absent.kind(), Kind::crashed) << absent.what();
  EXPECT_EQ(absent.frame(), SubjectError::kHandshake);
  EXPECT_TRUE(contains(absent.what(), "exited with status 127 (command not found?)")) << absent.what();
}

TEST(SubjectMethod, ProgramNameSkipsInterpreters) {
  EXPECT_EQ(program_name("python3 /opt/culler/run.py --fast"), "run.py");
  EXPECT_EQ(program_name("/usr/bin/env nice ./bin/culler"), "culler");
  EXPECT_EQ(program_name("  culler"), "culler");
  EXPECT_EQ(program_name(""), "subject");
  EXPECT_EQ(program_name("python3"), "python3");  // an interpreter alone is the program
}

}  // namespace
}  // namespace cullcheck
