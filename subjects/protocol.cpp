#include "subjects/protocol.hpp"

#include <algorithm>

#include "core/camera_matrices.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/utf8.hpp"
#include "core/scene_io.hpp"
#include "subjects/subject_error.hpp"

namespace cullcheck::protocol {
namespace {

using nlohmann::json;
using Kind = SubjectError::Kind;

json matrix_json(const Matrix4& m) {
  json rows = json::array();
  for (const auto& row : m) rows.push_back({row[0], row[1], row[2], row[3]});
  return rows;
}

json box_json(const Box3& b) { return {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.hi.y, b.hi.z}}; }

// A shortened copy of a line for error messages (subjects can print megabytes of garbage, and
// bytes that are not UTF-8, which JSON reports cannot hold).
std::string excerpt(const std::string& line) {
  std::string e = valid_utf8(line.size() > 120 ? line.substr(0, 120) + "..." : line);
  for (char& c : e)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  return "'" + e + "'";
}

json parse_object(const std::string& line, const std::string& subject, std::int64_t frame, const char* expected) {
  json message = json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (message.is_discarded())
    throw SubjectError(Kind::garbage, subject, frame, std::string("expected a JSON ") + expected + " message, got " + excerpt(line));
  if (!message.is_object())
    throw SubjectError(Kind::garbage, subject, frame, std::string("expected a JSON object (") + expected + "), got " + excerpt(line));
  return message;
}

}  // namespace

json hello(const Scene& scene, const SceneFiles& files, std::size_t frames) {
  json objects = json::array();
  // "node" is the object's node in the .glb (core/formats: building_<id> / mesh_<id>), "name" the
  // name it came with (an imported mesh's), else the node's.
  for (const Building& b : scene.buildings) {
    const std::string node = formats::building_node_name(b.id);
    objects.push_back({{"id", b.id}, {"node", node}, {"name", node}, {"kind", "building"}, {"bounds", box_json(b.bounds)}});
  }
  for (const MeshObject& m : scene.meshes) {
    const std::string node = formats::mesh_node_name(m.id);
    objects.push_back({{"id", m.id}, {"node", node}, {"name", m.name.empty() ? node : m.name}, {"kind", "mesh"}, {"bounds", box_json(m.bounds)}});
  }
  return {{"type", "hello"},
          {"protocol", kVersion},
          {"frames", frames},
          {"matrix_convention",
           "row-major m[row][col]; clip = projection * view * (x, y, z, 1) in scene-local metres, z up; eye space "
           "looks down -z (OpenGL); inside when -w <= x, y, z <= w"},
          {"scene",
           {{"glb", files.glb.empty() ? json(nullptr) : json(files.glb)},
            {"json", files.json},
            {"coordinates", "scene-local metres, z up; world = local + origin"},
            // The .glb's nodes sit under one root node that turns z up into glTF's +Y up: an engine
            // that keeps glTF's frame multiplies the view matrix by its inverse on the right.
            {"glb_root_node", "cullcheck_scene"},
            {"glb_root_matrix", {{1, 0, 0, 0}, {0, 0, 1, 0}, {0, -1, 0, 0}, {0, 0, 0, 1}}},
            {"origin", {scene.origin.x, scene.origin.y}},
            {"object_count", scene.object_count()},
            {"objects", std::move(objects)}}}};
}

std::string frame_line(std::size_t frame, double time_seconds, const Camera& camera) {
  const Resolution r = resolution_of(camera);
  const std::optional<Matrix4> projection = projection_matrix(camera);
  json message = {{"type", "frame"},
                  {"frame", frame},
                  {"time", time_seconds},
                  {"camera", json::parse(camera_to_json_text(camera))},
                  {"view", matrix_json(view_matrix(camera))},
                  {"projection", projection ? matrix_json(*projection) : json(nullptr)},
                  {"resolution", {r.width, r.height}}};
  return message.dump() + "\n";
}

std::string bye_line() { return R"({"type":"bye"})" "\n"; }

Claim parse_claim(const json& message, const std::string& subject, std::int64_t frame) {
  Claim claim;
  const auto it = message.find("claims");
  if (it == message.end() || !it->is_string())
    throw SubjectError(Kind::protocol, subject, frame, R"("claims" must be "conservative" or "approximate")");
  if (*it == "conservative") {
    if (message.contains("pixel_error_budget"))
      throw SubjectError(Kind::protocol, subject, frame, R"(a conservative subject has no "pixel_error_budget": it must show 0 misdrawn pixels)");
    return claim;
  }
  if (*it != "approximate")
    throw SubjectError(Kind::protocol, subject, frame, R"("claims" must be "conservative" or "approximate", got )" + it->dump());
  claim.conservative = false;
  const auto budget = message.find("pixel_error_budget");
  if (budget == message.end() || !budget->is_number_unsigned())
    throw SubjectError(Kind::protocol, subject, frame,
                       R"(an approximate subject must give "pixel_error_budget": the misdrawn pixels per frame it allows (an integer >= 0))");
  claim.pixel_error_budget = budget->get<std::uint64_t>();
  return claim;
}

Ready parse_ready(const std::string& line, const std::string& subject) {
  const json message = parse_object(line, subject, SubjectError::kHandshake, "ready");
  if (message.value("type", json()) != "ready")
    throw SubjectError(Kind::protocol, subject, SubjectError::kHandshake, R"(expected {"type":"ready",...}, got )" + excerpt(line));
  if (auto v = message.find("protocol"); v != message.end() && *v != kVersion)
    throw SubjectError(Kind::protocol, subject, SubjectError::kHandshake,
                       "speaks protocol " + v->dump() + "; cullcheck speaks " + std::to_string(kVersion));
  Ready ready;
  if (auto n = message.find("name"); n != message.end()) {
    if (!n->is_string() || n->get<std::string>().empty())
      throw SubjectError(Kind::protocol, subject, SubjectError::kHandshake, R"("name" must be a non-empty string)");
    ready.name = *n;
  }
  ready.claim = parse_claim(message, subject, SubjectError::kHandshake);
  if (auto p = message.find("projections"); p != message.end()) {
    if (!p->is_array())
      throw SubjectError(Kind::protocol, subject, SubjectError::kHandshake, R"("projections" must be an array of names)");
    ready.perspective = ready.orthographic = ready.omnidirectional = false;
    for (const json& name : *p) {
      if (name == "perspective") ready.perspective = true;
      else if (name == "orthographic") ready.orthographic = true;
      else if (name == "omnidirectional") ready.omnidirectional = true;
      else
        throw SubjectError(Kind::protocol, subject, SubjectError::kHandshake,
                           "unknown projection " + name.dump() + " (perspective, orthographic, omnidirectional)");
    }
  }
  return ready;
}

Visible parse_visible(const json& message, const std::string& subject, std::size_t frame, const std::vector<ObjectId>& known) {
  const auto at = static_cast<std::int64_t>(frame);
  if (auto t = message.find("type"); t != message.end() && *t != "visible")
    throw SubjectError(Kind::protocol, subject, at, R"(expected {"type":"visible",...}, got type )" + t->dump());
  const auto f = message.find("frame");
  if (f == message.end() || !f->is_number_unsigned())
    throw SubjectError(Kind::protocol, subject, at, R"("frame" must be the frame index, an integer >= 0)");
  if (f->get<std::uint64_t>() != frame)
    throw SubjectError(Kind::wrong_frame, subject, at, "answered frame " + f->dump() + ", expected " + std::to_string(frame));
  const auto ids = message.find("ids");
  if (ids == message.end() || !ids->is_array())
    throw SubjectError(Kind::protocol, subject, at, R"("ids" must be an array of the object ids not culled)");
  Visible out;
  out.frame = frame;
  out.ids.reserve(ids->size());
  for (const json& id : *ids) {
    if (!id.is_number_unsigned() || id.get<std::uint64_t>() > 0xFFFFFFFFULL)
      throw SubjectError(Kind::garbage, subject, at, "\"ids\" holds " + id.dump() + ", not an object id");
    out.ids.push_back(static_cast<ObjectId>(id.get<std::uint64_t>()));
  }
  std::sort(out.ids.begin(), out.ids.end());
  out.ids.erase(std::unique(out.ids.begin(), out.ids.end()), out.ids.end());
  for (ObjectId id : out.ids)
    if (!std::binary_search(known.begin(), known.end(), id))
      throw SubjectError(Kind::unknown_id, subject, at, "object " + std::to_string(id) + " is not in the scene");
  if (auto ms = message.find("cull_ms"); ms != message.end()) {
    if (!ms->is_number() || !(ms->get<double>() >= 0.0))
      throw SubjectError(Kind::protocol, subject, at, R"("cull_ms" must be a number >= 0)");
    out.cull_ms = ms->get<double>();
  }
  return out;
}

Visible parse_visible(const std::string& line, const std::string& subject, std::size_t frame, const std::vector<ObjectId>& known) {
  return parse_visible(parse_object(line, subject, static_cast<std::int64_t>(frame), "visible"), subject, frame, known);
}

}  // namespace cullcheck::protocol
