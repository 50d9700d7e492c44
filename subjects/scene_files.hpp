// The files a subject loads: the scene as cullcheck scene JSON and as glTF binary, written into
// a working folder (a fresh temporary one unless the user names one) so an engine loads exactly
// the geometry the oracle sees.
#pragma once

#include <string>

#include "core/scene.hpp"
#include "subjects/protocol.hpp"

namespace cullcheck {

// A folder for one run's files: a new one under $TMPDIR (or /tmp) when `path` is empty, removed
// with everything in it on destruction unless kept; a given folder is created if needed and
// never removed.
class WorkDir {
 public:
  explicit WorkDir(const std::string& path = "", bool keep = false);
  ~WorkDir();
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  void keep() { remove_ = false; }

 private:
  std::string path_;
  bool remove_ = false;
};

// Writes scene.json and (unless `glb` is false) scene.glb into `dir` (absolute paths returned);
// `prefix` names the files (e.g. "scene" -> scene.json, scene.glb).
protocol::SceneFiles write_scene_files(const Scene& scene, const std::string& dir, const std::string& prefix = "scene",
                                       bool glb = true);

}  // namespace cullcheck
