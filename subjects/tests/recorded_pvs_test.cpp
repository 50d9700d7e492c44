// RecordedPvsMethod (subjects/recorded_pvs.hpp): per-frame visible sets read from a JSON-lines
// file, in any order, with an optional ready line; repeated and missing frames are errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include "core/scene_io.hpp"
#include "subjects/tests/subject_error_of.hpp"
#include "subjects/recorded_pvs.hpp"
#include "subjects/subject_error.hpp"

namespace cullcheck {
namespace {

using Kind = SubjectError::Kind;
using test_support::error_of;

Scene three_buildings() {  // ids 1, 3, 5
  Scene s;
  s.buildings.push_back(box_building(1, 0, 0, 10, 10, 5));
  s.buildings.push_back(box_building(3, 20, 0, 30, 10, 5));
  s.buildings.push_back(box_building(5, 40, 0, 50, 10, 5));
  return s;
}

class RecordedPvs : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path, std::ios::binary) << text;
    paths_.push_back(path);
    return path;
  }
  void TearDown() override {
    for (const std::string& p : paths_) std::remove(p.c_str());
  }
  const Scene scene_ = three_buildings();
  const protocol::Claim conservative_{};

 private:
  std::vector<std::string> paths_;
};

TEST_F(RecordedPvs, ReadyLineAndFramesOutOfOrder) {
  const std::string path = write("recorded_out_of_order.jsonl",
                                 R"({"type":"ready","name":"baker","claims":"approximate","pixel_error_budget":12})"
                                 "\n"
                                 R"({"frame":2,"ids":[5,1,5]})"
                                 "\n\n"  // a blank line is skipped
                                 R"({"frame":0,"ids":[3]})"
                                 "\n"
                                 R"({"type":"visible","frame":1,"ids":[]})"
                                 "\n");
  RecordedPvsMethod m(scene_, path, conservative_);
  // The ready line overrides the name and the claim given.
  EXPECT_EQ(m.name(), "recorded:baker");
  EXPECT_FALSE(m.claims_conservative());
  EXPECT_EQ(m.pixel_error_budget(), std::optional<std::uint64_t>(12));
  EXPECT_EQ(m.frames_recorded(), 3u);
  EXPECT_EQ(m.unsupported_camera(Camera{}), "");
  m.set_frame(2, 0);
  EXPECT_EQ(m.cull(Camera{}).pvs, (std::vector<ObjectId>{1, 5}));  // sorted, duplicates removed
  m.set_frame(0, 0);
  EXPECT_EQ(m.cull(Camera{}).pvs, (std::vector<ObjectId>{3}));
  m.set_frame(1, 0);
  EXPECT_TRUE(m.cull(Camera{}).pvs.empty());
}

TEST_F(RecordedPvs, WithoutReadyLineTheGivenClaimAndTheFileNameApply) {
  const std::string path = write("recorded_plain.jsonl", "{\"frame\":0,\"ids\":[1,3]}\n");
  protocol::Claim approximate;
  approximate.conservative = false;
  approximate.pixel_error_budget = 9;
  RecordedPvsMethod m(scene_, path, approximate);
  EXPECT_EQ(m.name(), "recorded:recorded_plain.jsonl");
  EXPECT_FALSE(m.claims_conservative());
  EXPECT_EQ(m.pixel_error_budget(), std::optional<std::uint64_t>(9));
  // A name given to the constructor replaces the file name.
  RecordedPvsMethod n(scene_, path, approximate, "mine");
  EXPECT_EQ(n.name(), "recorded:mine");
}

TEST_F(RecordedPvs, ReadyLineClaimBeatsTheGivenClaim) {
  const std::string path = write("recorded_claim.jsonl", R"({"type":"ready","claims":"conservative"})"
                                                         "\n{\"frame\":0,\"ids\":[1]}\n");
  protocol::Claim approximate;
  approximate.conservative = false;
  approximate.pixel_error_budget = 9;
  RecordedPvsMethod m(scene_, path, approximate);
  EXPECT_TRUE(m.claims_conservative());
  EXPECT_FALSE(m.pixel_error_budget().has_value());
  EXPECT_EQ(m.name(), "recorded:recorded_claim.jsonl");  // the ready line has no name
}

// Regression test of a bug it found, since fixed (subjects/recorded_pvs.cpp, the file constructor): it takes a ready line's "name" only
// `if (... && name.empty())`, meaning a name given to the constructor wins (as SubjectOptions::name
// beats a subject's ready name); but the member initializer has already done
// `name_(... std::move(name))`, so `name` is a moved-from (in practice empty) string by then and
// the ready line's name always replaces the given one. Here "mine" becomes "baker". (The CLI passes
// no name today, so it does not show there yet. The header's mention of `claim_from_file` names a
// parameter that does not exist.)
TEST_F(RecordedPvs, GivenNameBeatsTheReadyLinesName) {
  const std::string path = write("recorded_named.jsonl", R"({"type":"ready","name":"baker","claims":"conservative"})"
                                                         "\n{\"frame\":0,\"ids\":[1]}\n");
  RecordedPvsMethod m(scene_, path, conservative_, "mine");
  EXPECT_EQ(m.name(), "recorded:mine");
}

TEST_F(RecordedPvs, RepeatedFrameIsAnError) {
  const std::string path = write("recorded_repeated.jsonl", "{\"frame\":0,\"ids\":[1]}\n{\"frame\":4,\"ids\":[3]}\n{\"frame\":0,\"ids\":[5]}\n");
  const SubjectError e = error_of([&] { RecordedPvsMethod m(scene_, path, conservative_); });
  EXPECT_EQ(e.kind(), Kind::protocol) << e.what();
  EXPECT_EQ(e.frame(), 0);
  EXPECT_EQ(std::string(e.what()),
            "recorded PVS file " + path + " line 3 at frame 0: protocol violation: gives this frame a second time");
}

TEST_F(RecordedPvs, MissingFrameIsAnErrorAtCullTime) {
  const std::string path = write("recorded_missing.jsonl", "{\"frame\":0,\"ids\":[1]}\n{\"frame\":2,\"ids\":[3]}\n");
  RecordedPvsMethod m(scene_, path, conservative_);  // reading succeeds: frames need not be contiguous
  m.set_frame(0, 0);
  EXPECT_EQ(m.cull(Camera{}).pvs, (std::vector<ObjectId>{1}));
  m.set_frame(1, 0);
  const SubjectError e = error_of([&] { (void)m.cull(Camera{}); });
  EXPECT_EQ(e.kind(), Kind::protocol) << e.what();
  EXPECT_EQ(e.frame(), 1);
  EXPECT_EQ(std::string(e.what()), "recorded PVS file " + path + " at frame 1: protocol violation: holds no line for this frame");
}

TEST_F(RecordedPvs, BadLinesNameTheirLine) {
  struct Case {
    const char* name;
    std::string text;
    Kind kind;
    std::string in_what;
  };
  const std::vector<Case> cases = {
      {"unknown id", "{\"frame\":0,\"ids\":[1]}\n{\"frame\":1,\"ids\":[2]}\n", Kind::unknown_id,
       " line 2 at frame 1: unknown id: object 2 is not in the scene"},
      {"not JSON", "{\"frame\":0,\"ids\":[1]}\nnot json\n", Kind::garbage, " line 2 during the handshake: garbage: is not a JSON object"},
      {"no frame", "{\"ids\":[1]}\n", Kind::protocol, " line 1 during the handshake: protocol violation: \"frame\" must be"},
      {"ready after frames", "{\"frame\":0,\"ids\":[1]}\n{\"type\":\"ready\",\"claims\":\"conservative\"}\n", Kind::protocol,
       " line 2 during the handshake: protocol violation: a ready line must come first"},
      {"bad claim", "{\"type\":\"ready\",\"claims\":\"approximate\"}\n", Kind::protocol,
       " line 1 during the handshake: protocol violation: an approximate subject must give"},
      {"ids not an array", "{\"frame\":0,\"ids\":1}\n", Kind::protocol, " line 1 at frame 0: protocol violation: \"ids\" must be"},
  };
  for (const Case& c : cases) {
    const std::string path = write("recorded_bad.jsonl", c.text);
    const SubjectError e = error_of([&] { RecordedPvsMethod m(scene_, path, conservative_); });
    EXPECT_EQ(e.kind(), c.kind) << c.name << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find("recorded PVS file " + path + c.in_what), std::string::npos) << c.name << ": " << e.what();
  }
  const SubjectError absent = error_of([&] { RecordedPvsMethod m(scene_, "/nonexistent/recorded.jsonl", conservative_); });
  EXPECT_EQ(absent.kind(), Kind::failed_to_start);
}

TEST_F(RecordedPvs, GivenVisibleSets) {
  using Frames = std::map<std::size_t, std::vector<ObjectId>>;
  RecordedPvsMethod m(scene_, Frames{{0, {5, 1, 1}}, {3, {}}}, conservative_, "given");
  EXPECT_EQ(m.name(), "recorded:given");
  EXPECT_EQ(m.frames_recorded(), 2u);
  m.set_frame(0, 0);
  EXPECT_EQ(m.cull(Camera{}).pvs, (std::vector<ObjectId>{1, 5}));
  m.set_frame(3, 0);
  EXPECT_TRUE(m.cull(Camera{}).pvs.empty());
  const SubjectError e = error_of([&] { RecordedPvsMethod bad(scene_, Frames{{0, {4}}}, conservative_, "given"); });
  EXPECT_EQ(e.kind(), Kind::unknown_id);
  EXPECT_EQ(e.frame(), 0);
}

}  // namespace
}  // namespace cullcheck
