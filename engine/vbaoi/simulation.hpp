// A deterministic discrete-event simulation of many VbAoI clients (thesis ch. 5.1, Fig. 5.3-5.4)
// and the baselines they are measured against, on one virtual clock.
//
// What runs:
//  - a server holding the whole graph (navigation_graph.hpp) and brokering the channels: it keeps
//    each client's subscriptions and fans every message published on a channel out to the
//    clients listening to it;
//  - clients that join at seeded times (initial phase: join request -> node id and coords ->
//    node data of the node and its SNs, with the PVSo buildings' geometry -> subscribe to PVSn
//    -> active), then walk the street graph: from a seeded point of their start node to seeded
//    points on shared edges, a random neighbour at a time (no U-turn unless at a dead end), at a
//    seeded walking speed. Every tick an active client moves and publishes its pose on its
//    node's channel (publish thread); it renders from its node's PVSo (render thread).
//  - handover: nearing the edge to the next node, a client subscribes to that node's PVSn; it
//    steps over only once it holds the node's data and the server has acknowledged the
//    subscription (otherwise it waits at the edge: a stall, counted). On crossing it publishes
//    leave on the old channel and welcome on the new one, asks for the new node's SNs it lacks
//    (prefetch, differential), drops node data outside the new node and its SNs, and drops the
//    channels it no longer needs after a grace period: the one-way latency bound, so that no
//    update published while it still could see the old node's listeners is routed after the
//    drop (see the channel-grouping argument in simulation.cpp).
//  - a network in process: each message takes latency + U[0, jitter) one way, links are FIFO
//    (as over TCP or a sequenced UDP channel), and each message is lost with probability `loss`
//    (drawn from a hash of its identity, so every policy meets the same losses). Control messages
//    are resent after `retry_timeout` until answered; pose updates are not.
//
// VbAoI filtered (issue 17: traffic against its physical limit): VbAoI's channels and control
// traffic, but the server forwards an update only to the listeners its sight filter
// (sight_filter.hpp) cannot prove blind to the sender: the sender's eye is the update's position,
// the listener may stand anywhere within speed_max x tick x |k - k_x| of the position of its
// latest update the server holds (tick k_x; one that has sent none is not filtered). Counted
// alongside like the baselines below (it does not drive the clients).
//
// Baselines on the same runs: the same clients, walks and publications are routed, in the same
// server, also as
//  - broadcast: every other client receives every update;
//  - neighbours: a client listens to its own node's channel and its SNs' only, as one sentence
//    of thesis ch. 5.1 puts it ("listens to the channel of nodes in SNs"; Fig. 5.2's item 4
//    says PVSn, which is what VbAoI here does); the server places a client by its join, welcome
//    and update messages;
//  - circular: an area of interest of radius R (the server forwards an update to the clients
//    whose last known position lies within R of the update's position).
// Only VbAoI's routing drives the clients; the baselines are counted alongside, pose traffic only
// (uplink and fan-out: none of them loads or asks for anything, so VbAoI's control messages and
// node data count against VbAoI alone).
//
// Checks (through a line-of-sight callback the caller gives: the oracle, in reports/ and
// properties/; the engine never includes it): at every `check_stride`-th tick, every pair of
// active clients whose eyes see each other must be mutually subscribed at the server (VbAoI) or
// within R (circular); each one's update of that tick must be routed to the other (a miss when
// not) and arrive (lost when the network dropped it). Every tick, every active client must hold
// the data of the node it renders from and stand inside it.
//
// Determinism: time is integer microseconds, ties are broken by event sequence numbers, and every
// random draw comes from core/random.hpp streams keyed by (seed, purpose, client) or a hash of a
// message's identity; `digest` hashes every client's node and position at every tick.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.hpp"
#include "engine/vbaoi/messages.hpp"
#include "engine/vbaoi/navigation_graph.hpp"

namespace cullcheck::vbaoi {

struct SimulationOptions {
  std::uint64_t seed = 1;
  std::uint32_t clients = 100;
  double duration = 20.0;       // simulated seconds, from the first join
  double tick = 0.1;            // seconds between pose updates (10 Hz)
  double join_window = 2.0;     // clients join at seeded times in [0, join_window)
  double speed_min = 1.0;       // walking speed range, m/s
  double speed_max = 2.0;
  double latency = 0.04;        // one-way base latency client <-> server, seconds
  double jitter = 0.02;         // plus U[0, jitter)
  double loss = 0.0;            // probability that a message is lost
  double retry_timeout = 0.25;  // seconds before a control message is resent
  std::vector<double> circular_radii = {50.0, 100.0, 200.0};
  std::uint32_t check_stride = 1;  // line of sight checked at every k-th tick
};

// Throws std::invalid_argument naming the field when an option is out of range.
void validate(const SimulationOptions& options);

// Pairs (i, j), i < j, of indices into `eyes` whose eyes see each other.
using LineOfSight = std::function<std::vector<std::pair<std::uint32_t, std::uint32_t>>(const std::vector<Vec3>& eyes)>;

// A pair of clients that saw each other at a checked tick while a policy did not group them.
struct GroupingExample {
  std::uint64_t tick = 0;
  std::uint32_t a = 0, b = 0;  // clients
  Vec2 position_a, position_b;
  NodeId node_a = 0, node_b = 0;
};

struct PolicyTraffic {
  std::string policy;            // "vbaoi", "vbaoi_filtered", "broadcast", "neighbours", "circular" (in that order)
  double radius = 0.0;           // circular only
  std::uint64_t messages = 0;    // every message sent: updates up, deliveries down, control
  std::uint64_t bytes = 0;
  std::uint64_t update_deliveries = 0;  // pose updates delivered to listeners (fan-out)
  // ... of updates sent at checked ticks: beside visible_updates (the deliveries an interest
  // manager that knew every line of sight would make at those ticks, the traffic's physical
  // limit), the policy's cost over that limit.
  std::uint64_t checked_update_deliveries = 0;
  std::vector<std::uint64_t> messages_per_tick;  // by tick of sending
  std::vector<std::uint64_t> bytes_per_tick;
  // Correctness, over the checked ticks:
  std::uint64_t visible_updates = 0;   // (observer, visible client's update) pairs expected
  std::uint64_t missed_updates = 0;    // ... not routed to the observer
  std::uint64_t lost_updates = 0;      // ... routed, but lost by the network
  std::uint64_t grouping_violations = 0;  // visible pairs not mutually subscribed (neighbours: nodes neither
                                          // equal nor adjacent; circular: farther apart than R)
  std::vector<GroupingExample> first_violations;  // the first few, in tick order
};

struct SimulationResult {
  SimulationOptions options;
  std::uint32_t nodes = 0;
  std::uint64_t ticks = 0;
  std::uint64_t checked_ticks = 0;
  std::uint64_t active_client_ticks = 0;
  std::uint64_t pairs_checked = 0;      // pairs of active clients whose line of sight was tested
  std::uint64_t visible_pairs = 0;
  std::vector<PolicyTraffic> policies;  // vbaoi, vbaoi_filtered, broadcast, neighbours, circular per radius
  // VbAoI's own:
  std::array<std::uint64_t, kMessageKinds> messages_by_kind{};  // sent, by kind
  std::array<std::uint64_t, kMessageKinds> bytes_by_kind{};
  std::uint64_t handovers = 0;
  std::uint64_t stall_ticks = 0;          // client ticks spent waiting at an edge
  std::uint64_t resent = 0;               // control messages sent again after a timeout
  std::uint64_t render_violations = 0;    // active client ticks rendering a node it does not hold
  std::uint64_t outside_node = 0;         // active client ticks outside the node it is in
  std::uint32_t clients_active = 0;       // clients that completed the initial phase
  std::vector<double> join_seconds;       // per client: join request to active
  std::vector<std::uint64_t> join_bytes;  // per client: bytes received in the initial phase
  std::vector<double> listened_channels;  // per active client tick: channels subscribed at the server
  std::uint64_t whole_city_bytes = 0;     // every building's geometry: what a client without VbAoI loads
  std::uint64_t digest = 0;               // hash of every client's node and position at every tick
  double wall_seconds = 0.0;
  double line_of_sight_seconds = 0.0;     // of it, in the callback
};

SimulationResult simulate(const Scene& scene, const NavigationGraph& graph, const SimulationOptions& options,
                          const LineOfSight& line_of_sight);

}  // namespace cullcheck::vbaoi
