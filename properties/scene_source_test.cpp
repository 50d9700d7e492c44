// SceneSource (reports/scene_source.hpp): a scene file of any kind loads through
// formats::read_scene_file_any with the source's import options, and the replay flags name the
// options that are not the defaults, so a replay reads the file the same way.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"
#include "generators/city.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {
namespace {

TEST(SceneSource, LoadsMeshFilesAndReplaysTheirImportOptions) {
  const Scene city = generators::make_city("manhattan", 2, {{"blocks_x", 1}, {"blocks_y", 1}});
  const std::string glb = (std::filesystem::temp_directory_path() / "cullcheck_scene_source_test.glb").string();
  formats::write_glb(city, glb);
  SceneSource source;
  source.file = glb;
  EXPECT_EQ(source.replay_flags(), "--scene '" + glb + "'");
  EXPECT_EQ(scene_to_json_text(source.load()), scene_to_json_text(city));
  source.mesh_ids = formats::IdSource::mesh;
  EXPECT_EQ(source.replay_flags(), "--scene '" + glb + "' --mesh-ids mesh");
  EXPECT_EQ(source.load().ids(), city.ids());
  source.obj_up = formats::UpAxis::y;
  EXPECT_EQ(source.replay_flags(), "--scene '" + glb + "' --mesh-ids mesh --obj-up y");
  std::filesystem::remove(glb);
}

}  // namespace
}  // namespace cullcheck
