// cullcheck generate: a city (scene JSON, optionally OBJ) and optionally a camera path.
#include <iostream>
#include <memory>
#include <sstream>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::cli {

Runner add_generate(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    PathFlags path;
    std::string output = "scene.json", obj, path_output;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand("generate", "Generate a city (JSON, optionally OBJ) and optionally a camera path");
  f->scene.add(*sub);
  f->path.add(*sub, 300);
  sub->add_option("--output,-o", f->output, "Scene JSON file to write")->capture_default_str();
  sub->add_option("--obj", f->obj, "Also write the scene as Wavefront OBJ");
  sub->add_option("--path-output", f->path_output, "Also write a camera path (see --path-kind) to this file");
  return [f] {
    const Scene scene = f->scene.source.load();
    write_scene_file(scene, f->output);
    std::cout << "wrote " << f->output << ": " << scene.buildings.size() << " buildings, " << scene.triangle_count()
              << " triangles\n";
    if (!f->obj.empty()) {
      std::ostringstream obj;
      write_obj(scene, obj);
      write_text_file_atomically(f->obj, obj.str());
      std::cout << "wrote " << f->obj << "\n";
    }
    if (!f->path_output.empty()) {
      const CameraPath path = f->path.load(scene);
      write_text_file_atomically(f->path_output, path_to_json_text(path));
      std::cout << "wrote " << f->path_output << ": " << path.frames.size() << " frames\n";
    }
    return 0;
  };
}

}  // namespace cullcheck::cli
