// Writes the fuzzers' seed corpus (fuzz/CMakeLists.txt runs it at build time): small scenes,
// cameras and paths from the seeded generators, written by cullcheck's own writers in every
// format a harness reads, and the subject protocol's lines. Small on purpose: libFuzzer's
// default input length follows the largest seed, and small inputs mutate fast.
//
// Usage: fuzz_seed_corpus OUT_DIR   (writes OUT_DIR/<harness>/<seed>)
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tiny_gltf.h>

#include "core/camera.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "subjects/protocol.hpp"

namespace fs = std::filesystem;
using namespace cullcheck;

namespace {

fs::path out_dir;

void put(const std::string& harness, const std::string& name, const std::string& bytes) {
  const fs::path dir = out_dir / harness;
  fs::create_directories(dir);
  std::ofstream out(dir / name, std::ios::binary | std::ios::trunc);
  out << bytes;
  if (!out) throw std::runtime_error("cannot write " + (dir / name).string());
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The same .glb as a .gltf text file with its buffer embedded as a data URI.
std::string gltf_text(const std::string& glb) {
  tinygltf::Model model;
  tinygltf::TinyGLTF io;
  std::string err, warn;
  if (!io.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                               static_cast<unsigned int>(glb.size())))
    throw std::runtime_error("cannot re-read a written .glb: " + err);
  std::ostringstream text;
  if (!io.WriteGltfSceneToStream(&model, text, false, false)) throw std::runtime_error("cannot write .gltf text");
  return text.str();
}

std::vector<std::pair<std::string, Scene>> scenes() {
  std::vector<std::pair<std::string, Scene>> out;
  generators::ManhattanParams manhattan;
  manhattan.blocks_x = manhattan.blocks_y = 2;
  manhattan.buildings_per_block = 1;
  out.emplace_back("manhattan", generators::manhattan_city(manhattan, 1));
  generators::IrregularParams irregular;
  irregular.count = 3;
  irregular.area_size = 60;
  out.emplace_back("irregular", generators::irregular_city(irregular, 2));
  generators::OpeningsParams openings;
  openings.blocks_x = openings.blocks_y = 1;
  openings.core_buildings = 1;
  openings.bridge_count = 0;
  out.emplace_back("openings", generators::openings_city(openings, 3));
  // Far from the origin: the readers rebase it.
  Scene far;
  far.buildings.push_back(box_building(7, 5'000'000.0, 4'000'000.0, 5'000'010.5, 4'000'004.25, 12.5));
  rebase_if_far(far);
  out.emplace_back("far", far);
  // One mesh object and one building, ids not from 0.
  Scene mixed;
  mixed.buildings.push_back(box_building(40, 0, 0, 4, 3, 6));
  MeshObject m;
  m.id = 41;
  m.name = "tetra";
  m.vertices = {{10, 0, 0}, {12, 0, 0}, {10, 2, 0}, {10, 0, 2}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  validate_and_finish(m);
  mixed.meshes.push_back(m);
  out.emplace_back("mixed", mixed);
  return out;
}

std::vector<std::pair<std::string, Camera>> cameras() {
  std::vector<std::pair<std::string, Camera>> out;
  Camera eye;
  eye.position = {1.5, -20.25, 1.7};
  eye.yaw = 0.5;
  out.emplace_back("perspective", eye);
  Camera tilted = eye;
  tilted.pitch = -0.3, tilted.roll = 0.2, tilted.width = 320, tilted.height = 200;
  out.emplace_back("tilted_resolution", tilted);
  Camera panorama = eye;
  panorama.hfov = kTwoPi;
  out.emplace_back("panorama", panorama);
  Camera ortho = eye;
  ortho.projection = Projection::orthographic;
  ortho.ortho_width = 100, ortho.ortho_height = 80;
  ortho.position.z = 200, ortho.pitch = -kPi / 2;
  out.emplace_back("orthographic", ortho);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_seed_corpus OUT_DIR\n";
    return 2;
  }
  out_dir = argv[1];
  try {
    for (const auto& [name, scene] : scenes()) {
      put("fuzz_scene_json", name + ".json", scene_to_json_text(scene));
      const std::string glb = formats::glb_bytes(scene);
      put("fuzz_gltf", name + ".glb", glb);
      put("fuzz_gltf", name + ".gltf", gltf_text(glb));
      const std::string obj = (out_dir / (name + ".obj.tmp")).string();
      formats::write_obj(scene, obj);
      put("fuzz_obj", name + ".obj", file_bytes(obj));
      fs::remove(obj);
    }
    // GeoJSON footprints: local metres with storeys, holes, a MultiPolygon, a spike and a bow tie;
    // longitude/latitude; a named UTM CRS.
    put("fuzz_geojson", "local.geojson",
        R"({"type":"FeatureCollection","features":[)"
        R"({"type":"Feature","properties":{"floors":3},"geometry":{"type":"Polygon","coordinates":[[[0,0],[10,0],[10,10],[0,10],[0,0]],[[2,2],[3,2],[3,3],[2,2]]]}},)"
        R"({"type":"Feature","properties":{"floors":"2"},"geometry":{"type":"MultiPolygon","coordinates":[[[[20,0],[24,0],[24,4],[20,0]]],[[[30,0],[34,0],[34,0],[34,4],[38,4],[34,4],[30,4],[30,0]]]]}},)"
        R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[0,20],[5,25],[5,20],[0,25],[0,20]]]}},)"
        R"({"type":"Feature","properties":{"floors":1},"geometry":{"type":"Point","coordinates":[1,1]}}]})");
    put("fuzz_geojson", "lonlat.geojson",
        R"({"type":"Feature","properties":{"height":12},"geometry":{"type":"Polygon","coordinates":[[[-71.0,42.0],[-70.999,42.0],[-70.999,42.001],[-71.0,42.0]]]}})");
    put("fuzz_geojson", "utm.geojson",
        R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::26919"}},"features":[)"
        R"({"type":"Feature","properties":{"height":9.5},"geometry":{"type":"Polygon","coordinates":[[[329000.5,4691000.25],[329020.5,4691000.25],[329020.5,4691020.25],[329000.5,4691000.25]]]}}]})");
    // CityJSON: a Building with a GroundSurface and measuredHeight, one of two parts (one
    // without semantics), a TINRelief; a 1.0 file without a transform.
    const std::string cube = R"([[[[0,1,5,4]],[[1,2,6,5]],[[2,3,7,6]],[[3,0,4,7]],[[4,5,6,7]],[[0,3,2,1]]]])";
    const std::string cube_vertices = R"([0,0,0],[200,0,0],[200,100,0],[0,100,0],[0,0,400],[200,0,400],[200,100,400],[0,100,400])";
    put("fuzz_cityjson", "parts.city.json",
        R"({"type":"CityJSON","version":"1.1","transform":{"scale":[0.01,0.01,0.01],"translate":[100,200,3]},"CityObjects":{)"
        R"("a":{"type":"Building","attributes":{"measuredHeight":7.5,"RelativeRidgeHeight":4},"geometry":[{"type":"Solid","lod":"2.2","boundaries":)" +
            cube + R"(,"semantics":{"surfaces":[{"type":"WallSurface"},{"type":"GroundSurface"}],"values":[[0,0,0,0,0,1]]}}]},)"
        R"("b":{"type":"Building","children":["b1"]},"b1":{"type":"BuildingPart","parents":["b"],"geometry":[{"type":"MultiSurface","lod":2,"boundaries":[[[0,1,2,3]],[[4,5,6,7]]]}]},)"
        R"("t":{"type":"TINRelief","geometry":[{"type":"CompositeSurface","lod":1,"boundaries":[[[0,1,2]]]}]}},"vertices":[)" +
            cube_vertices + "]}");
    put("fuzz_cityjson", "plain.city.json",
        R"({"type":"CityJSON","version":"1.0","CityObjects":{"x":{"type":"Building","geometry":[{"type":"MultiSolid","lod":1,"boundaries":[)" + cube +
            R"(]}]}},"vertices":[[0,0,0],[2,0,0],[2,1,0],[0,1,0],[0,0,4],[2,0,4],[2,1,4],[0,1,4]]})");
    // Hand-written shapes the writers never produce: y-up OBJ with polygons and negative indices.
    put("fuzz_obj", "polygons.obj", "o quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\ng tri\nv 0 0 1\nf -1 -2 -3\n");
    put("fuzz_scene_json", "version2_named.json",
        R"({"format":"cullcheck-scene","version":2,"origin":[100,200],"buildings":[],)"
        R"("meshes":[{"id":3,"name":"wall","vertices":[[0,0,0],[1,0,0],[0,0,1]],"triangles":[[0,1,2]]}]})");

    for (const auto& [name, camera] : cameras()) put("fuzz_camera_json", name + ".json", camera_to_json_text(camera));
    put("fuzz_camera_json", "aspect.json", R"({"position":[0,0,2],"vfov":0.8,"aspect":1.5,"near":0.5,"far":900})");
    put("fuzz_camera_json", "ortho_aspect.json",
        R"({"position":[0,0,50],"projection":"orthographic","ortho_height":40,"resolution":[640,480]})");

    generators::ManhattanParams city;
    city.blocks_x = city.blocks_y = 2;
    generators::StreetWalkParams walk;
    walk.frames = 4;
    put("fuzz_path_json", "street_walk.json", path_to_json_text(generators::street_walk(city, walk, 5)));
    CameraPath by_hand;
    by_hand.kind = "by_hand";
    by_hand.frames_per_second = 24;
    for (const auto& [name, camera] : cameras()) by_hand.frames.push_back(camera);
    put("fuzz_path_json", "every_projection.json", path_to_json_text(by_hand));

    // What a subject sends: ready lines, then visible lines (frames 0 and 3, ids the harness knows).
    put("fuzz_protocol", "ready_conservative", R"({"type":"ready","protocol":1,"name":"c","claims":"conservative"})");
    put("fuzz_protocol", "ready_approximate",
        R"({"type":"ready","name":"a","claims":"approximate","pixel_error_budget":40,"projections":["perspective","orthographic","omnidirectional"]})");
    put("fuzz_protocol", "visible_0", R"({"type":"visible","frame":0,"ids":[3,1,1,21],"cull_ms":0.25})");
    put("fuzz_protocol", "visible_3", R"({"type":"visible","frame":3,"ids":[4294967295,0,13]})");
    put("fuzz_recorded_pvs", "ready_and_frames.jsonl",
        "{\"type\":\"ready\",\"name\":\"baker\",\"claims\":\"conservative\"}\n{\"frame\":1,\"ids\":[5,0]}\n"
        "{\"type\":\"visible\",\"frame\":0,\"ids\":[1,2,3]}\n\n{\"frame\":3,\"ids\":[]}\n{\"frame\":2,\"ids\":[8]}\n");
    put("fuzz_recorded_pvs", "approximate.jsonl",
        "{\"type\":\"ready\",\"claims\":\"approximate\",\"pixel_error_budget\":7}\r\n{\"frame\":0,\"ids\":[0,1,2,3,5,8]}\r\n");
  } catch (const std::exception& e) {
    std::cerr << "fuzz_seed_corpus: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
