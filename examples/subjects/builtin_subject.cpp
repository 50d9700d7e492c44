// A built-in method wrapped as an outside subject over the subject protocol (README "The
// subject protocol"): it loads the scene JSON the hello names and answers every frame with the
// named method's PVS. The gate must pass it, with exactly the PVS and violations the same
// method gives in-process (properties/cli_test.sh checks both).
//
//   builtin_subject [METHOD]     default oh_os_conservative; frustum on a scene with mesh objects
//                                (for any 2.5D METHOD, which does not model them)
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/elapsed.hpp"
#include "core/scene_io.hpp"
#include "engine/method.hpp"

int main(int argc, char** argv) {
  using nlohmann::json;
  namespace cc = cullcheck;
  std::ios::sync_with_stdio(false);
  std::string line;
  if (!std::getline(std::cin, line)) return 1;
  const json hello = json::parse(line);
  const cc::Scene scene = cc::read_scene_file(hello["scene"]["json"].get<std::string>());
  std::string name = argc > 1 ? argv[1] : "oh_os_conservative";
  // 2.5D methods do not model mesh objects: there the subject is frustum culling, and its ready
  // message says so (the fuzzer draws mesh scenes too; ci/mutants/ fuzzes 2.5D methods this way).
  if (!scene.prisms_only() && name != "frustum") {
    if (argc > 1) std::cerr << "builtin_subject: " << name << " does not run on mesh objects; answering with frustum\n";
    name = "frustum";
  }
  const auto method = cc::make_method(name, scene);
  cc::Camera ortho;
  ortho.projection = cc::Projection::orthographic;
  ortho.ortho_width = ortho.ortho_height = 1.0;
  const bool orthographic = method->unsupported_camera(ortho).empty();
  json projections = {"perspective", "omnidirectional"};
  if (orthographic) projections.push_back("orthographic");
  // A method that does not claim conservativeness is measured, not gated: approximate, with a
  // budget no frame can exceed.
  json ready = {{"type", "ready"}, {"name", "builtin-" + name}, {"projections", projections}};
  ready["claims"] = method->claims_conservative() ? "conservative" : "approximate";
  if (!method->claims_conservative()) ready["pixel_error_budget"] = std::uint64_t(cc::kMaxImageSide) * cc::kMaxImageSide;
  std::cout << ready.dump() << std::endl;
  while (std::getline(std::cin, line)) {
    const json request = json::parse(line);
    if (request["type"] != "frame") break;
    const cc::Camera camera = cc::camera_from_json_text(request["camera"].dump());
    const auto start = std::chrono::steady_clock::now();
    const cc::CullResult r = method->cull(camera);
    const double ms = cc::ms_since(start);
    std::cout << json{{"type", "visible"}, {"frame", request["frame"]}, {"ids", r.pvs}, {"cull_ms", ms}}.dump() << std::endl;
  }
  return 0;
}
