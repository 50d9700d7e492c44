// What VbAoI's clients and server say to each other (thesis ch. 5.1, Fig. 5.3-5.4), and what each
// message costs on the wire. The simulation (simulation.hpp) counts messages and bytes with these
// sizes; they are UDP payloads (no IP/UDP headers), fixed here so that reports compare policies
// on one scale:
//  - every message: a 16-byte header (u8 kind, 3 bytes padding, u32 sender, u32 channel or node,
//    u32 sequence or request id);
//  - a pose: position and yaw/pitch/roll as six f32 = 24 bytes;
//  - id lists: u32 count + 4 bytes per id;
//  - node data (Fig. 5.2): node id, coords (u32 count + two f32 per vertex), PVSo, PVSn, SNs;
//  - a building's geometry: id, height, footprint (u32 count + two f32 per vertex).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/scene.hpp"
#include "engine/vbaoi/navigation_graph.hpp"

namespace cullcheck::vbaoi {

enum class MessageKind : std::uint8_t {
  join_request,       // client -> server: starting position (initial phase)
  join_reply,         // server -> client: node id and coords
  node_request,       // client -> server: a node, with its SNs, and the nodes already held
  node_reply,         // server -> client: node data of the node and SNs missing, and the geometry of
                      // the PVSo buildings the client does not hold yet (differential, Fig. 5.7)
  subscribe,          // client -> server: channels to add (a node's PVSn)
  unsubscribe,        // client -> server: channels to drop
  ack,                // server -> client: a subscribe or unsubscribe was applied
  update,             // client -> channel: pose (publish thread), fanned out to listeners
  welcome,            // client -> channel of the node entered: pose
  leave,              // client -> channel of the node left
};
constexpr std::size_t kMessageKinds = 10;
std::string_view message_kind_name(MessageKind kind);

constexpr std::size_t kHeaderBytes = 16;
constexpr std::size_t kPoseBytes = 24;
constexpr std::size_t id_list_bytes(std::size_t ids) { return 4 + 4 * ids; }

inline std::size_t node_data_bytes(const NavigationNode& n) {
  return 4 + (4 + 8 * n.coords.size()) + id_list_bytes(n.pvs_o.size()) + id_list_bytes(n.pvs_n.size()) +
         id_list_bytes(n.neighbours.size());
}
inline std::size_t building_bytes(const Building& b) { return 4 + 4 + 4 + 8 * b.footprint.size(); }
// Every building's geometry: what a client without VbAoI loads.
inline std::uint64_t whole_city_bytes(const Scene& scene) {
  std::uint64_t bytes = 0;
  for (const Building& b : scene.buildings) bytes += building_bytes(b);
  return bytes;
}

}  // namespace cullcheck::vbaoi
