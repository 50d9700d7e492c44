// Flags that name outside subjects (gate and report): programs over the subject protocol,
// recorded visible-set files and one camera's inline visible set, and how their failures replay.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/cullcheck/flags.hpp"
#include "reports/verification.hpp"
#include "subjects/protocol.hpp"
#include "subjects/scene_files.hpp"

namespace cullcheck::cli {

struct SubjectFlags {
  std::vector<std::string> subjects, pvs_files;
  std::string visible, claims = "conservative", work_dir;
  std::int64_t pixel_budget = -1;
  double frame_timeout = 10.0, hello_timeout = 60.0;
  bool keep_work_dir = false, no_glb = false;

  // `inline_visible`: also --visible/--claims/--pixel-budget (gate only).
  void add(CLI::App& app, bool inline_visible);
  bool any() const { return !subjects.empty() || !pvs_files.empty() || !visible.empty(); }
  // The flags that change what the subjects answer (shards of one run must share them).
  nlohmann::json identity() const {
    return {{"subjects", subjects}, {"pvs_files", pvs_files}, {"visible", visible}, {"claims", claims}, {"pixel_budget", pixel_budget}};
  }

  // Appends a method per subject to `methods`. `path_flags` rebuild the path (empty when the run
  // is one camera); a program that fails its handshake sets `aborted` and is not added.
  void build(const Scene& scene, const SceneSource& source, const CameraPath& path, const std::string& path_flags,
             std::vector<MethodUnderTest>& methods, std::optional<Abort>& aborted);
  // The built-in methods named `builtin` and these subjects along `path` (verify_path): a subject
  // whose handshake fails stops the run before its first frame (`aborted`), and every subject
  // has said bye and exited when this returns. With `require_any`, nothing to check is an
  // InputError.
  PathVerification verify(const Scene& scene, const SceneSource& source, const CameraPath& path, const std::string& path_flags,
                          const std::vector<std::string>& builtin, const MethodOptions& method_options,
                          const VerificationOptions& options, bool require_any);

 private:
  std::unique_ptr<WorkDir> work_;
};

}  // namespace cullcheck::cli
