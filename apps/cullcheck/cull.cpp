// cullcheck cull: one engine method for a camera or along a path, its PVS as JSON lines; with
// --recorded FILE also as a recorded-PVS file (`gate --pvs FILE`, README "The gate"), so a
// method's answers on one scene can be held to the oracle on another with the same ids (prisms
// against their LoD2 meshes).
#include <iostream>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::cli {

Runner add_cull(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    MethodFlags tuning;
    CoordinateFlags coordinates;
    std::string method = "oh_os_conservative", camera, path, recorded;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand("cull", "Run one engine method for a camera and print its PVS as JSON");
  f->scene.add(*sub);
  f->tuning.add(*sub);
  sub->add_option("--method", f->method, "Engine method")->capture_default_str();
  auto* camera = sub->add_option("--camera", f->camera, "Camera as JSON (see --coordinates)");
  auto* path = sub->add_option("--path", f->path, "Camera path file: prints one JSON line per frame");
  camera->excludes(path);
  sub->add_option("--recorded", f->recorded,
                  "Also write the PVSs as a recorded-PVS file for `cullcheck gate --pvs` (a ready line naming the method "
                  "and, when it claims it, conservativeness; then {\"frame\":i,\"ids\":[...]} per frame)");
  f->coordinates.add(*sub, "--camera and --path");
  return [f] {
    const Scene scene = f->scene.source.load();
    auto method = make_method(f->method, scene, f->tuning.options);
    if (f->camera.empty() && f->path.empty())
      throw InputError("command line", "camera", "give a camera (--camera JSON) or a path (--path FILE)");
    std::vector<Camera> cameras;
    if (!f->path.empty()) {
      CameraPath path = read_path_file(f->path);
      f->coordinates.localise(path, scene, f->path);
      cameras = std::move(path.frames);
    } else {
      cameras.push_back(f->coordinates.camera(scene, f->camera, "--camera"));
    }
    std::string recorded;
    if (!f->recorded.empty()) {
      nlohmann::json ready = {{"type", "ready"}, {"name", f->method}};
      if (method->claims_conservative()) ready["claims"] = "conservative";
      recorded = ready.dump() + "\n";
    }
    for (std::size_t frame = 0; frame < cameras.size(); ++frame) {
      if (const std::string why = method->unsupported_camera(cameras[frame]); !why.empty())
        throw InputError(f->path.empty() ? "camera" : "path frame " + std::to_string(frame), "projection", why);
      const CullResult result = method->cull(cameras[frame]);
      nlohmann::json out = pvs_json(result);
      out["method"] = f->method;
      if (!f->path.empty()) out["frame"] = frame;
      std::cout << out.dump() << "\n";
      if (!f->recorded.empty()) recorded += nlohmann::json{{"frame", frame}, {"ids", result.pvs}}.dump() + "\n";
    }
    if (!f->recorded.empty()) write_text_file_atomically(f->recorded, recorded);
    return 0;
  };
}

}  // namespace cullcheck::cli
