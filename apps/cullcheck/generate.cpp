// cullcheck generate: a city (scene JSON, optionally glTF binary and OBJ) and optionally a camera path.
#include <iostream>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/formats/footprint_formats.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::cli {

Runner add_generate(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    PathFlags path;
    std::string output = "scene.json", obj, glb, path_output;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand("generate", "Generate a city (JSON, optionally OBJ) and optionally a camera path");
  f->scene.add(*sub);
  f->path.add(*sub, 300);
  sub->add_option("--output,-o", f->output, "Scene JSON file to write")->capture_default_str();
  sub->add_option("--obj", f->obj, "Also write the scene as Wavefront OBJ (one group per object, z up, scene-local)");
  sub->add_option("--glb", f->glb, "Also write the scene as glTF 2.0 binary (one node per object, named by its id)");
  sub->add_option("--path-output", f->path_output, "Also write a camera path (see --path-kind) to this file");
  return [f] {
    formats::ImportReport imported;
    const Scene scene = f->scene.source.load(&imported);
    if (imported.features > 0) {
      std::cout << "imported " << formats::footprint_import_summary(imported) << "\n";
      for (const std::string& n : imported.notes) std::cout << "  " << n << "\n";
    }
    write_scene_file(scene, f->output);
    std::cout << "wrote " << f->output << ": " << scene.buildings.size() << " buildings, " << scene.meshes.size()
              << " mesh objects, " << scene.triangle_count() << " triangles\n";
    if (!f->obj.empty()) {
      formats::write_obj(scene, f->obj);
      std::cout << "wrote " << f->obj << "\n";
    }
    if (!f->glb.empty()) {
      formats::write_glb(scene, f->glb);
      std::cout << "wrote " << f->glb << "\n";
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
