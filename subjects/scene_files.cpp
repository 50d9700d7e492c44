#include "subjects/scene_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck {

WorkDir::WorkDir(const std::string& path, bool keep) {
  namespace fs = std::filesystem;
  if (!path.empty()) {
    std::error_code ec;
    fs::create_directories(path, ec);
    if (ec || !fs::is_directory(path)) throw InputError("folder " + path, "(folder)", "cannot be created");
    path_ = fs::absolute(path).string();
    return;
  }
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/cullcheck-XXXXXX";
  // An unusable TMPDIR is the environment's fault, like an unwritable --output: bad input, not a bug.
  if (!::mkdtemp(pattern.data()))
    throw InputError("TMPDIR " + std::string(tmp && *tmp ? tmp : "/tmp"), "(folder)",
                     "cannot hold a temporary folder (give --work-dir DIR, or a writable TMPDIR)");
  path_ = pattern;
  remove_ = !keep;
}

WorkDir::~WorkDir() {
  if (!remove_) return;
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

protocol::SceneFiles write_scene_files(const Scene& scene, const std::string& dir, const std::string& prefix, bool glb) {
  protocol::SceneFiles files;
  files.json = std::filesystem::absolute(dir + "/" + prefix + ".json").string();
  write_scene_file(scene, files.json);
  if (!glb) return files;
  files.glb = std::filesystem::absolute(dir + "/" + prefix + ".glb").string();
  formats::write_glb(scene, files.glb);
  return files;
}

}  // namespace cullcheck
