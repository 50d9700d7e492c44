// The subject protocol's messages (subjects/protocol.hpp): the ready and visible answers a subject
// sends, each error's kind and the frame its message names, and the hello and frame requests
// cullcheck sends, with literal values.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/camera_matrices.hpp"
#include "core/scene_io.hpp"
#include "subjects/protocol.hpp"
#include "subjects/subject_error.hpp"

namespace cullcheck {
namespace {

using nlohmann::json;
using Kind = SubjectError::Kind;

const std::string kSubject = "subject 'x'";

// The SubjectError `f` throws (a failure when it throws nothing).
SubjectError error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const SubjectError& e) {
    return e;
  }
  ADD_FAILURE() << "no SubjectError thrown";
  return SubjectError(Kind::protocol, "(none)", 0, "(none)");
}

SubjectError ready_error(const std::string& line) {
  return error_of([&] { (void)protocol::parse_ready(line, kSubject); });
}

// --- ready ---------------------------------------------------------------------------------------

TEST(ParseReady, ConservativeClaim) {
  const protocol::Ready r = protocol::parse_ready(R"({"type":"ready","name":"culler","claims":"conservative"})", kSubject);
  EXPECT_EQ(r.name, "culler");
  EXPECT_TRUE(r.claim.conservative);
  EXPECT_FALSE(r.claim.pixel_error_budget.has_value());
  // Without "projections": perspective cameras only.
  EXPECT_TRUE(r.perspective);
  EXPECT_FALSE(r.orthographic);
  EXPECT_FALSE(r.omnidirectional);
}

TEST(ParseReady, ApproximateClaimWithBudgetAndProjections) {
  const protocol::Ready r = protocol::parse_ready(
      R"({"type":"ready","protocol":1,"claims":"approximate","pixel_error_budget":40,"projections":["orthographic","omnidirectional"]})",
      kSubject);
  EXPECT_EQ(r.name, "");  // optional
  EXPECT_FALSE(r.claim.conservative);
  ASSERT_TRUE(r.claim.pixel_error_budget.has_value());
  EXPECT_EQ(*r.claim.pixel_error_budget, 40u);
  EXPECT_FALSE(r.perspective);  // listing projections replaces the default
  EXPECT_TRUE(r.orthographic);
  EXPECT_TRUE(r.omnidirectional);
  // A budget of 0 is a budget.
  EXPECT_EQ(protocol::parse_ready(R"({"type":"ready","claims":"approximate","pixel_error_budget":0})", kSubject)
                .claim.pixel_error_budget,
            std::optional<std::uint64_t>(0));
}

// A line the reader must refuse: the error's kind and a part of its message.
struct ErrorCase {
  const char* name;
  std::string line;
  Kind kind;
  const char* in_message;
};

TEST(ParseReady, ErrorsAreProtocolViolationsDuringTheHandshake) {
  const std::vector<ErrorCase> cases = {
      {"missing claims", R"({"type":"ready","name":"c"})", Kind::protocol, R"("claims" must be)"},
      {"claims not a string", R"({"type":"ready","claims":true})", Kind::protocol, R"("claims" must be)"},
      {"unknown claim", R"({"type":"ready","claims":"exact"})", Kind::protocol, R"(got "exact")"},
      {"budget on a conservative claim", R"({"type":"ready","claims":"conservative","pixel_error_budget":3})",
       Kind::protocol, "a conservative subject has no"},
      {"approximate without budget", R"({"type":"ready","claims":"approximate"})", Kind::protocol,
       R"(must give "pixel_error_budget")"},
      {"negative budget", R"({"type":"ready","claims":"approximate","pixel_error_budget":-1})", Kind::protocol,
       R"(must give "pixel_error_budget")"},
      {"fractional budget", R"({"type":"ready","claims":"approximate","pixel_error_budget":1.5})", Kind::protocol,
       R"(must give "pixel_error_budget")"},
      {"wrong protocol version", R"({"type":"ready","protocol":2,"claims":"conservative"})", Kind::protocol,
       "speaks protocol 2; cullcheck speaks 1"},
      {"unknown projection", R"({"type":"ready","claims":"conservative","projections":["perspective","fisheye"]})",
       Kind::protocol, R"(unknown projection "fisheye")"},
      {"projections not an array", R"({"type":"ready","claims":"conservative","projections":"perspective"})",
       Kind::protocol, R"("projections" must be an array)"},
      {"empty name", R"({"type":"ready","name":"","claims":"conservative"})", Kind::protocol, R"("name" must be)"},
      {"wrong type", R"({"type":"visible","claims":"conservative"})", Kind::protocol, R"(expected {"type":"ready")"},
      {"not JSON", "READY!", Kind::garbage, "expected a JSON ready message, got 'READY!'"},
      {"not an object", "[1,2]", Kind::garbage, "expected a JSON object (ready)"},
  };
  for (const ErrorCase& c : cases) {
    const SubjectError e = ready_error(c.line);
    EXPECT_EQ(e.kind(), c.kind) << c.name << ": " << e.what();
    EXPECT_EQ(e.frame(), SubjectError::kHandshake) << c.name;
    EXPECT_EQ(e.subject(), kSubject) << c.name;
    EXPECT_NE(std::string(e.what()).find(kSubject + " during the handshake: "), std::string::npos) << c.name << ": " << e.what();
    EXPECT_NE(e.problem().find(c.in_message), std::string::npos) << c.name << ": " << e.what();
  }
}

TEST(ParseReady, WholeMessageOfAVersionError) {
  EXPECT_STREQ(ready_error(R"({"type":"ready","protocol":2,"claims":"conservative"})").what(),
               "subject 'x' during the handshake: protocol violation: speaks protocol 2; cullcheck speaks 1");
}

TEST(ParseReady, GarbageIsShortenedAndControlCharactersMasked) {
  // 200 'a's then a tab: the excerpt keeps 120 characters and "...", and control characters
  // become '?'.
  const SubjectError long_line = ready_error(std::string(200, 'a'));
  EXPECT_NE(long_line.problem().find("'" + std::string(120, 'a') + "...'"), std::string::npos) << long_line.what();
  EXPECT_EQ(long_line.problem().find(std::string(121, 'a')), std::string::npos);
  EXPECT_NE(ready_error("a\tb").problem().find("'a?b'"), std::string::npos);
}

// --- visible -------------------------------------------------------------------------------------

const std::vector<ObjectId> kKnown = {1, 3, 5};

SubjectError visible_error(const std::string& line, std::size_t frame = 4) {
  return error_of([&] { (void)protocol::parse_visible(line, kSubject, frame, kKnown); });
}

TEST(ParseVisible, DuplicatesRemovedAndSorted) {
  const protocol::Visible v =
      protocol::parse_visible(std::string(R"({"type":"visible","frame":4,"ids":[5,1,5,3,1],"cull_ms":0.25})"), kSubject, 4, kKnown);
  EXPECT_EQ(v.frame, 4u);
  EXPECT_EQ(v.ids, (std::vector<ObjectId>{1, 3, 5}));
  ASSERT_TRUE(v.cull_ms.has_value());
  EXPECT_EQ(*v.cull_ms, 0.25);
  // "type" and "cull_ms" are optional; an empty set is an answer.
  const protocol::Visible none = protocol::parse_visible(std::string(R"({"frame":0,"ids":[]})"), kSubject, 0, kKnown);
  EXPECT_TRUE(none.ids.empty());
  EXPECT_FALSE(none.cull_ms.has_value());
  // The parsed-object overload gives the same (parsed JSON holds non-negative integers as
  // unsigned, so the object is built from unsigned values).
  const json parsed = {{"frame", 2u}, {"ids", {3u, 3u}}};
  EXPECT_EQ(protocol::parse_visible(parsed, kSubject, 2, kKnown).ids, (std::vector<ObjectId>{3}));
}

TEST(ParseVisible, ErrorsNameTheKindAndTheFrame) {
  const std::vector<ErrorCase> cases = {
      {"wrong frame", R"({"type":"visible","frame":3,"ids":[1]})", Kind::wrong_frame, "answered frame 3, expected 4"},
      {"unknown id", R"({"frame":4,"ids":[1,2]})", Kind::unknown_id, "object 2 is not in the scene"},
      {"negative id", R"({"frame":4,"ids":[1,-1]})", Kind::garbage, R"("ids" holds -1, not an object id)"},
      {"id beyond 2^32", R"({"frame":4,"ids":[4294967296]})", Kind::garbage, "holds 4294967296"},
      {"string id", R"({"frame":4,"ids":["1"]})", Kind::garbage, R"(holds "1")"},
      {"ids not an array", R"({"frame":4,"ids":5})", Kind::protocol, R"("ids" must be an array)"},
      {"ids missing", R"({"frame":4})", Kind::protocol, R"("ids" must be an array)"},
      {"frame missing", R"({"ids":[1]})", Kind::protocol, R"("frame" must be the frame index)"},
      {"frame a string", R"({"frame":"4","ids":[1]})", Kind::protocol, R"("frame" must be the frame index)"},
      {"frame negative", R"({"frame":-4,"ids":[1]})", Kind::protocol, R"("frame" must be the frame index)"},
      {"negative cull_ms", R"({"frame":4,"ids":[1],"cull_ms":-0.5})", Kind::protocol, R"("cull_ms" must be)"},
      {"cull_ms a string", R"({"frame":4,"ids":[1],"cull_ms":"fast"})", Kind::protocol, R"("cull_ms" must be)"},
      {"wrong type", R"({"type":"ready","frame":4,"ids":[1]})", Kind::protocol, R"(got type "ready")"},
      {"not JSON", "this is not JSON", Kind::garbage, "expected a JSON visible message"},
  };
  for (const ErrorCase& c : cases) {
    const SubjectError e = visible_error(c.line);
    EXPECT_EQ(e.kind(), c.kind) << c.name << ": " << e.what();
    EXPECT_EQ(e.frame(), 4) << c.name;
    EXPECT_NE(std::string(e.what()).find("subject 'x' at frame 4: "), std::string::npos) << c.name << ": " << e.what();
    EXPECT_NE(e.problem().find(c.in_message), std::string::npos) << c.name << ": " << e.what();
  }
}

// Regression test of a bug it found, since fixed (subjects/protocol.cpp, excerpt()): a garbage line is quoted into the error with only bytes
// below 0x20 masked, so bytes that are not UTF-8 (a subject printing binary, here 0xFF 0xFE) reach
// SubjectError::what(), and from there Abort::message and the gate's check message. JSON text must
// be UTF-8: nlohmann::json's dump() throws type_error 316 on it, so `cullcheck gate` cannot write
// report.json for such a subject and ends with an internal error instead of exit code 2 (see
// GateVerdict.SubjectGarbageThatIsNotUtf8StillGivesAWritableVerdict).
TEST(ParseVisible, GarbageExcerptIsValidUtf8) {
  const SubjectError e = visible_error(std::string("\xff\xfe not JSON"));
  EXPECT_EQ(e.kind(), Kind::garbage);
  EXPECT_NO_THROW((void)json(std::string(e.what())).dump()) << "what() holds bytes that are not UTF-8";
}

TEST(ParseVisible, WholeMessageOfAWrongFrame) {
  EXPECT_STREQ(visible_error(R"({"frame":3,"ids":[1]})").what(), "subject 'x' at frame 4: wrong frame: answered frame 3, expected 4");
  EXPECT_STREQ(visible_error(R"({"frame":0,"ids":[7]})", 0).what(), "subject 'x' at frame 0: unknown id: object 7 is not in the scene");
}

// --- frame and hello requests ----------------------------------------------------------------------

Camera square_camera() {
  Camera c;
  c.hfov = c.vfov = kPi / 2;
  c.near = 1;
  c.far = 100;
  c.width = 64, c.height = 48;
  return c;
}

TEST(FrameLine, HoldsTheMatricesAndTheResolution) {
  const std::string line = protocol::frame_line(7, 0.5, square_camera());
  ASSERT_FALSE(line.empty());
  EXPECT_EQ(line.back(), '\n');
  EXPECT_EQ(line.find('\n'), line.size() - 1);  // exactly one line
  const json m = json::parse(line);
  EXPECT_EQ(m["type"], "frame");
  EXPECT_EQ(m["frame"], 7);
  EXPECT_EQ(m["time"], 0.5);
  EXPECT_EQ(m["resolution"], (json{64, 48}));
  EXPECT_EQ(m["camera"], json::parse(camera_to_json_text(square_camera())));
  // Eye at the origin looking along +x: V's rows right (0,-1,0), up (0,0,1), -forward (-1,0,0).
  const double view[4][4] = {{0, -1, 0, 0}, {0, 0, 1, 0}, {-1, 0, 0, 0}, {0, 0, 0, 1}};
  // hfov = vfov = pi/2, near 1, far 100: P = [[1,0,0,0],[0,1,0,0],[0,0,-101/99,-200/99],[0,0,-1,0]].
  const double projection[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -101.0 / 99, -200.0 / 99}, {0, 0, -1, 0}};
  ASSERT_EQ(m["view"].size(), 4u);
  ASSERT_EQ(m["projection"].size(), 4u);
  for (int r = 0; r < 4; ++r) {
    ASSERT_EQ(m["view"][r].size(), 4u);
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(m["view"][r][c].get<double>(), view[r][c], 1e-12) << "view[" << r << "][" << c << "]";
      EXPECT_NEAR(m["projection"][r][c].get<double>(), projection[r][c], 1e-12) << "projection[" << r << "][" << c << "]";
    }
  }
}

TEST(FrameLine, DefaultResolutionAndNoProjectionAt360Degrees) {
  Camera c;  // hfov pi/3, vfov pi/4: 320 x round(320 tan(pi/8) / tan(pi/6)) = 320 x 230
  EXPECT_EQ(json::parse(protocol::frame_line(0, 0, c))["resolution"], (json{320, 230}));
  c.hfov = kTwoPi;  // a panorama: 320 x 160, and P is null
  const json m = json::parse(protocol::frame_line(1, 0.04, c));
  EXPECT_EQ(m["resolution"], (json{320, 160}));
  EXPECT_TRUE(m["projection"].is_null());
  EXPECT_EQ(m["view"].size(), 4u);
}

TEST(Hello, ListsEveryObjectWithIdNodeKindAndBounds) {
  Scene scene;
  scene.buildings.push_back(box_building(7, 0, 0, 10, 8, 12));
  MeshObject arch;
  arch.id = 9;
  arch.name = "arch";
  arch.vertices = {{20, 0, 0}, {21, 0, 0}, {20, 1, 0}, {20, 0, 1}};
  arch.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  validate_and_finish(arch);
  MeshObject unnamed = arch;
  unnamed.id = 11;
  unnamed.name = "";
  scene.meshes = {arch, unnamed};
  const json h = protocol::hello(scene, {"/tmp/s.glb", "/tmp/s.json"}, 3);
  EXPECT_EQ(h["type"], "hello");
  EXPECT_EQ(h["protocol"], 1);
  EXPECT_EQ(h["frames"], 3);
  EXPECT_EQ(h["scene"]["glb"], "/tmp/s.glb");
  EXPECT_EQ(h["scene"]["json"], "/tmp/s.json");
  EXPECT_EQ(h["scene"]["object_count"], 3);
  EXPECT_EQ(h["scene"]["origin"], (json{0.0, 0.0}));
  const json expected = json::parse(R"([
    {"id":7,"node":"building_7","name":"building_7","kind":"building","bounds":[[0,0,0],[10,8,12]]},
    {"id":9,"node":"mesh_9","name":"arch","kind":"mesh","bounds":[[20,0,0],[21,1,1]]},
    {"id":11,"node":"mesh_11","name":"mesh_11","kind":"mesh","bounds":[[20,0,0],[21,1,1]]}])");
  EXPECT_EQ(h["scene"]["objects"], expected);
  // Without a glTF file "glb" is null.
  EXPECT_TRUE(protocol::hello(scene, {"", "/tmp/s.json"}, 3)["scene"]["glb"].is_null());
  // One line when dumped (the protocol is JSON lines).
  EXPECT_EQ(h.dump().find('\n'), std::string::npos);
  EXPECT_EQ(protocol::bye_line(), "{\"type\":\"bye\"}\n");
}

}  // namespace
}  // namespace cullcheck
