#include "engine/vbaoi/simulation.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <queue>
#include <stdexcept>
#include <unordered_map>

#include "core/elapsed.hpp"
#include "core/random.hpp"
#include "engine/vbaoi/sight_filter.hpp"

// Why VbAoI routes every visible update (the channel-grouping argument the properties check):
// let client x see client y at tick t, x in node A, y in node B. The graph puts B in PVSn(A)
// (navigation_graph.hpp). x entered A only when every channel of PVSn(A) was confirmed: its latest
// subscribe/unsubscribe request was an acknowledged subscribe, so the server held x on channel B
// at t and nothing x had sent could still remove it. y's update of t, published on B, reaches
// the server at most one latency bound L = latency + jitter later (links are FIFO, and y sent
// nothing later before it). A channel leaves x's subscriptions only through an unsubscribe sent
// at least L after the last moment x wanted it, and x wanted B at t, so that unsubscribe arrives
// no earlier than t + L, and at a tie after the update (events at one time run in sending order).
// So the update is routed to x. Stalls, not misses, are what latency and loss cost. (A first
// version counted a channel as held while its unsubscribe was in flight: the property found it.)

namespace cullcheck::vbaoi {
namespace {

using Micros = std::int64_t;
Micros micros(double seconds) { return static_cast<Micros>(std::llround(seconds * 1e6)); }

// Order of SimulationResult::policies.
constexpr std::size_t kVbaoi = 0, kFiltered = 1, kBroadcast = 2, kNeighbours = 3, kFirstCircular = 4;
constexpr std::size_t kExamples = 3;  // grouping violations kept per policy
constexpr std::uint64_t kWalkStream = 0x57414C4B;     // "WALK"
constexpr std::uint64_t kNetworkStream = 0x4E455457;  // "NETW"

// A uniform [0, 1) draw from a hash: the same message identity gets the same draw in any order.
double hashed_uniform(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  return static_cast<double>(hash_mix(hash_mix(hash_mix(seed, a), b), c) >> 11) * 0x1.0p-53;
}

bool contains(const std::vector<std::uint32_t>& v, std::uint32_t x) { return std::binary_search(v.begin(), v.end(), x); }
void insert_sorted(std::vector<std::uint32_t>& v, std::uint32_t x) {
  const auto it = std::lower_bound(v.begin(), v.end(), x);
  if (it == v.end() || *it != x) v.insert(it, x);
}
void erase_sorted(std::vector<std::uint32_t>& v, std::uint32_t x) {
  const auto it = std::lower_bound(v.begin(), v.end(), x);
  if (it != v.end() && *it == x) v.erase(it);
}
std::vector<std::uint32_t> set_union(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  std::vector<std::uint32_t> out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}
std::vector<std::uint32_t> set_minus(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  std::vector<std::uint32_t> out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}
bool includes(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  return std::includes(a.begin(), a.end(), b.begin(), b.end());
}

struct Message {
  MessageKind kind = MessageKind::update;
  std::uint32_t client = 0;   // the client sending or addressed
  std::uint32_t channel = 0;  // update/welcome/leave: channel; join_reply/node_request: node
  std::uint64_t request = 0;  // control: request id; update: tick
  std::vector<std::uint32_t> ids;
  std::vector<std::uint32_t> held;  // node_request: nodes held
  Vec2 position;
  std::size_t bytes = 0;
};

Message make(MessageKind kind) {
  Message m;
  m.kind = kind;
  return m;
}

enum class EventType : std::uint8_t { tick, server_receive, client_receive, retry, release };
struct Event {
  Micros time;
  std::uint64_t seq;
  EventType type;
  std::uint32_t client;  // retry/release: the client
  std::uint64_t ref;     // tick: its index; retry: request id
  Message message;
};
struct Later {
  bool operator()(const Event& a, const Event& b) const { return a.time != b.time ? a.time > b.time : a.seq > b.seq; }
};

enum class Phase : std::uint8_t { waiting, joining, loading, subscribing, active };

struct Client {
  Phase phase = Phase::waiting;
  Micros join_at = 0, join_started = 0;
  std::uint64_t join_bytes = 0;
  Random walk{0};
  double speed = 1.0;
  Vec2 pos;
  double yaw = 0.0;
  NodeId node = 0, next = 0, previous = 0;
  bool has_next = false, presubscribed = false;
  Vec2 waypoint;
  std::vector<std::uint32_t> held;       // node data held
  std::vector<std::uint32_t> wanted;     // channels it needs now
  // A channel is confirmed when its latest subscribe/unsubscribe request is an acknowledged
  // subscribe: then the server holds it, and nothing the client sent since can remove it.
  std::vector<std::uint32_t> confirmed;
  std::map<std::uint32_t, std::uint64_t> latest;  // channel -> its latest subscribe/unsubscribe request
  std::map<std::uint32_t, Micros> last_wanted;  // channel -> when it stopped being wanted
  std::map<std::uint64_t, Message> outstanding; // control requests waiting for an answer
};

class Simulation {
 public:
  Simulation(const Scene& scene, const NavigationGraph& graph, const SimulationOptions& o, const LineOfSight& los)
      : scene_(scene), graph_(graph), o_(o), los_(los), sight_(scene, graph.options.eye_height) {
    tick_ = micros(o.tick);
    bound_ = micros(o.latency + o.jitter);
    ticks_ = static_cast<std::uint64_t>(std::floor(o.duration / o.tick)) + 1;
    r_.options = o;
    r_.nodes = static_cast<std::uint32_t>(graph.nodes.size());
    auto policy = [&](const char* name, double radius) {
      PolicyTraffic p;
      p.policy = name;
      p.radius = radius;
      r_.policies.push_back(p);
    };
    policy("vbaoi", 0.0);
    policy("vbaoi_filtered", 0.0);
    policy("broadcast", 0.0);
    policy("neighbours", 0.0);
    for (double radius : o.circular_radii) policy("circular", radius);
    for (PolicyTraffic& p : r_.policies) {
      p.messages_per_tick.assign(ticks_, 0);
      p.bytes_per_tick.assign(ticks_, 0);
    }
    checked_tick_.assign(ticks_, 0);
    r_.whole_city_bytes = whole_city_bytes(scene);
    building_index_.reserve(scene.buildings.size());
    for (std::uint32_t b = 0; b < scene.buildings.size(); ++b) building_index_[scene.buildings[b].id] = b;
    subs_.resize(o.clients);
    members_.resize(graph.nodes.size());
    known_.assign(o.clients, 0);
    server_node_.assign(o.clients, 0);
    clients_in_.assign(graph.nodes.size(), 0);
    last_pos_.resize(o.clients);
    update_pos_.resize(o.clients);
    update_tick_.assign(o.clients, kNoTick);
    cell_of_.assign(o.clients, std::nullopt);
    grid_size_ = 1.0;
    for (double radius : o.circular_radii) grid_size_ = std::max(grid_size_, radius);
    setup_clients();
  }

  SimulationResult run() {
    const auto start = std::chrono::steady_clock::now();
    for (std::uint32_t c = 0; c < o_.clients; ++c) push_event(clients_[c].join_at, EventType::retry, c, 0, {});
    for (std::uint64_t k = 0; k < ticks_; ++k) push_event(static_cast<Micros>(k) * tick_, EventType::tick, 0, k, {});
    const Micros end = static_cast<Micros>(ticks_ - 1) * tick_;
    while (!events_.empty() && events_.top().time <= end) {
      Event e = events_.top();
      events_.pop();
      now_ = e.time;
      switch (e.type) {
        case EventType::tick: on_tick(e.ref); break;
        case EventType::server_receive: on_server(e.message); break;
        case EventType::client_receive: on_client(e.message); break;
        case EventType::retry: on_retry(e.client, e.ref); break;
        case EventType::release: on_release(e.client); break;
      }
    }
    // Expectations whose update never reached the server before the end are not counted.
    for (const Client& c : clients_) r_.clients_active += c.phase == Phase::active ? 1 : 0;
    r_.ticks = ticks_;
    r_.wall_seconds = seconds_since(start);
    return std::move(r_);
  }

 private:
  // --- setup -------------------------------------------------------------------------------
  void setup_clients() {
    // Start nodes drawn by area, so clients spread evenly over the street space.
    std::vector<double> cumulative;
    double total = 0.0;
    for (const NavigationNode& n : graph_.nodes) {
      total += std::abs(signed_area(n.coords));
      cumulative.push_back(total);
    }
    clients_.resize(o_.clients);
    for (std::uint32_t c = 0; c < o_.clients; ++c) {
      Client& cl = clients_[c];
      cl.walk = Random::stream(o_.seed, kWalkStream, c);
      cl.join_at = micros(cl.walk.uniform_real(0.0, o_.join_window));
      cl.speed = cl.walk.uniform_real(o_.speed_min, o_.speed_max);
      const double pick = cl.walk.uniform_real(0.0, total);
      const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), pick);
      cl.node = static_cast<NodeId>(std::min<std::size_t>(it - cumulative.begin(), graph_.nodes.size() - 1));
      cl.pos = random_point_in(graph_.nodes[cl.node].coords, cl.walk);
    }
  }

  // --- events and the network --------------------------------------------------------------
  void push_event(Micros time, EventType type, std::uint32_t client, std::uint64_t ref, Message message) {
    events_.push({time, seq_++, type, client, ref, std::move(message)});
  }
  std::size_t tick_index(Micros t) const {
    return std::min<std::size_t>(static_cast<std::size_t>(t / tick_), ticks_ - 1);
  }
  // Counts a message against `policy` at the current time.
  void count(std::size_t policy, std::size_t messages, std::size_t bytes, std::size_t tick) {
    PolicyTraffic& p = r_.policies[policy];
    p.messages += messages;
    p.bytes += bytes;
    p.messages_per_tick[tick] += messages;
    p.bytes_per_tick[tick] += bytes;
  }
  // VbAoI's channel traffic (control messages, uplinks, welcome and leave), which VbAoI filtered
  // shares: only their pose deliveries differ.
  void count_channels(std::size_t messages, std::size_t bytes, std::size_t tick) {
    count(kVbaoi, messages, bytes, tick);
    count(kFiltered, messages, bytes, tick);
  }
  // Sends one control or update message over a client's link (up: to the server; down: to the
  // client). VbAoI's traffic; baselines count their own. Returns false when the network lost it.
  bool send(Message m, bool up) {
    const std::size_t kind = static_cast<std::size_t>(m.kind);
    r_.messages_by_kind[kind] += 1;
    r_.bytes_by_kind[kind] += m.bytes;
    count_channels(1, m.bytes, tick_index(now_));
    const std::uint64_t id = message_id_++;
    if (hashed_uniform(o_.seed ^ kNetworkStream, id, 1, 0) < o_.loss) return false;
    const double delay = o_.latency + o_.jitter * hashed_uniform(o_.seed ^ kNetworkStream, id, 2, 0);
    Micros& last = up ? link_up_[m.client] : link_down_[m.client];
    last = std::max(last, now_ + micros(delay));
    push_event(last, up ? EventType::server_receive : EventType::client_receive, m.client, 0, std::move(m));
    return true;
  }
  std::uint64_t request(Client& cl, std::uint32_t c, Message m) {
    m.request = next_request_++;
    m.client = c;
    if (m.kind == MessageKind::subscribe || m.kind == MessageKind::unsubscribe)
      for (std::uint32_t ch : m.ids) {
        cl.latest[ch] = m.request;
        if (m.kind == MessageKind::unsubscribe) erase_sorted(cl.confirmed, ch);  // no longer sure
      }
    cl.outstanding[m.request] = m;
    send(m, true);
    push_event(now_ + micros(o_.retry_timeout), EventType::retry, c, m.request, {});
    return m.request;
  }

  // --- clients -----------------------------------------------------------------------------
  void on_retry(std::uint32_t c, std::uint64_t id) {
    Client& cl = clients_[c];
    if (id == 0) {  // the join timer
      if (cl.phase != Phase::waiting) return;
      cl.phase = Phase::joining;
      cl.join_started = now_;
      Message m = make(MessageKind::join_request);
      m.position = cl.pos;
      m.bytes = kHeaderBytes + 12;
      request(cl, c, m);
      return;
    }
    auto it = cl.outstanding.find(id);
    if (it == cl.outstanding.end()) return;
    Message m = it->second;
    if (m.kind == MessageKind::subscribe || m.kind == MessageKind::unsubscribe) {
      // Resend only what this request still decides: a channel with a later request is that
      // request's business (links are FIFO, so a resend must not overtake it at the server).
      std::vector<std::uint32_t> ids;
      for (std::uint32_t ch : m.ids)
        if (cl.latest[ch] == id) ids.push_back(ch);
      if (m.kind == MessageKind::unsubscribe) ids = releasable(cl, ids);  // wanted again: resubscribed already
      if (ids.empty()) {
        cl.outstanding.erase(it);
        return;
      }
      m.ids = ids;
      m.bytes = kHeaderBytes + id_list_bytes(m.ids.size());
      it->second = m;
    }
    ++r_.resent;
    send(m, true);
    push_event(now_ + micros(o_.retry_timeout), EventType::retry, c, id, {});
  }

  void on_client(const Message& m) {
    Client& cl = clients_[m.client];
    const auto it = cl.outstanding.find(m.request);
    if (it == cl.outstanding.end()) return;  // a duplicate answer
    const Message asked = it->second;
    cl.outstanding.erase(it);
    if (cl.phase == Phase::joining || cl.phase == Phase::loading || cl.phase == Phase::subscribing)
      cl.join_bytes += m.bytes;
    switch (m.kind) {
      case MessageKind::join_reply:
        cl.node = m.channel;
        cl.phase = Phase::loading;
        ask_node(cl, m.client, cl.node);
        break;
      case MessageKind::node_reply:
        for (std::uint32_t n : m.ids) insert_sorted(cl.held, n);
        if (cl.phase == Phase::loading && contains(cl.held, cl.node)) {
          cl.phase = Phase::subscribing;
          cl.wanted = graph_.nodes[cl.node].pvs_n;
          subscribe_missing(cl, m.client, cl.wanted);
        }
        break;
      case MessageKind::ack:
        if (asked.kind == MessageKind::subscribe)
          for (std::uint32_t ch : asked.ids)
            if (cl.latest[ch] == asked.request) insert_sorted(cl.confirmed, ch);
        if (cl.phase == Phase::subscribing && includes(cl.confirmed, graph_.nodes[cl.node].pvs_n)) {
          cl.phase = Phase::active;
          r_.join_seconds.push_back(static_cast<double>(now_ - cl.join_started) * 1e-6);
          r_.join_bytes.push_back(cl.join_bytes);
          choose_next(cl);
        }
        break;
      default: break;
    }
  }

  void ask_node(Client& cl, std::uint32_t c, NodeId node) {
    for (const auto& [id, m] : cl.outstanding)
      if (m.kind == MessageKind::node_request && m.channel == node) return;
    Message m = make(MessageKind::node_request);
    m.channel = node;
    m.held = cl.held;
    m.bytes = kHeaderBytes + id_list_bytes(m.held.size());
    request(cl, c, m);
  }
  // Channels whose latest request is a subscribe still unanswered.
  std::vector<std::uint32_t> pending_subscriptions(const Client& cl) const {
    std::vector<std::uint32_t> out;
    for (const auto& [id, m] : cl.outstanding)
      if (m.kind == MessageKind::subscribe)
        for (std::uint32_t ch : m.ids)
          if (cl.latest.at(ch) == id) out.push_back(ch);
    std::sort(out.begin(), out.end());
    return out;
  }
  void subscribe_missing(Client& cl, std::uint32_t c, const std::vector<std::uint32_t>& channels) {
    const std::vector<std::uint32_t> missing = set_minus(set_minus(channels, cl.confirmed), pending_subscriptions(cl));
    if (missing.empty()) return;
    Message m = make(MessageKind::subscribe);
    m.ids = missing;
    m.bytes = kHeaderBytes + id_list_bytes(missing.size());
    request(cl, c, m);
  }
  // Channels that may be dropped now: not wanted, and not wanted within the last latency bound.
  std::vector<std::uint32_t> releasable(const Client& cl, const std::vector<std::uint32_t>& candidates) const {
    std::vector<std::uint32_t> out;
    for (std::uint32_t ch : candidates) {
      if (contains(cl.wanted, ch)) continue;
      const auto it = cl.last_wanted.find(ch);
      if (it != cl.last_wanted.end() && it->second + bound_ > now_) continue;
      out.push_back(ch);
    }
    return out;
  }
  void on_release(std::uint32_t c) {
    Client& cl = clients_[c];
    const std::vector<std::uint32_t> subscribed = set_union(cl.confirmed, pending_subscriptions(cl));
    const std::vector<std::uint32_t> drop = releasable(cl, subscribed);
    if (drop.empty()) return;
    Message m = make(MessageKind::unsubscribe);
    m.ids = drop;
    m.bytes = kHeaderBytes + id_list_bytes(drop.size());
    request(cl, c, m);
  }

  void choose_next(Client& cl) {
    const NavigationNode& here = graph_.nodes[cl.node];
    cl.has_next = false;
    cl.presubscribed = false;
    if (here.neighbours.empty()) return;
    std::vector<NodeId> options;
    for (NodeId n : here.neighbours)
      if (n != cl.previous || here.neighbours.size() == 1) options.push_back(n);
    if (options.empty()) options = here.neighbours;
    const NodeId next = options[static_cast<std::size_t>(cl.walk.uniform_int(0, static_cast<std::int64_t>(options.size()) - 1))];
    const auto edge = shared_edge(here.coords, graph_.nodes[next].coords);
    if (!edge) return;
    const double f = cl.walk.uniform_real(0.15, 0.85);
    cl.next = next;
    cl.waypoint = edge->first + (edge->second - edge->first) * f;
    cl.has_next = true;
  }
  bool ready_to_enter(const Client& cl) const {
    return contains(cl.held, cl.next) && includes(cl.confirmed, graph_.nodes[cl.next].pvs_n);
  }
  void handover(Client& cl, std::uint32_t c) {
    const NodeId from = cl.node, to = cl.next;
    Message leave = make(MessageKind::leave);
    leave.client = c;
    leave.channel = from;
    leave.bytes = kHeaderBytes;
    send(leave, true);
    Message welcome = make(MessageKind::welcome);
    welcome.client = c;
    welcome.channel = to;
    welcome.position = cl.pos;
    welcome.bytes = kHeaderBytes + kPoseBytes;
    send(welcome, true);
    ++r_.handovers;
    for (std::uint32_t ch : cl.wanted) cl.last_wanted[ch] = now_;
    cl.previous = from;
    cl.node = to;
    cl.wanted = graph_.nodes[to].pvs_n;
    // Keep the data of the new node and its SNs (the default AoI of Fig. 5.6a); fetch the rest.
    std::vector<std::uint32_t> keep = graph_.nodes[to].neighbours;
    insert_sorted(keep, to);
    cl.held.erase(std::remove_if(cl.held.begin(), cl.held.end(), [&](std::uint32_t n) { return !contains(keep, n); }),
                  cl.held.end());
    ask_node(cl, c, to);
    push_event(now_ + bound_ + 1, EventType::release, c, 0, {});
    choose_next(cl);
  }
  void move(Client& cl, std::uint32_t c) {
    double remaining = cl.speed * o_.tick;
    while (remaining > 0.0 && cl.has_next) {
      const Vec2 d = cl.waypoint - cl.pos;
      const double dist = length(d);
      if (dist > remaining) {
        cl.pos = cl.pos + d * (remaining / dist);
        cl.yaw = std::atan2(d.y, d.x);
        break;
      }
      cl.pos = cl.waypoint;
      remaining -= dist;
      if (!ready_to_enter(cl)) {
        ++r_.stall_ticks;
        presubscribe(cl, c);
        break;
      }
      handover(cl, c);
    }
    // Nearing the edge: subscribe to the next node's PVSn in time for the acknowledgement (a
    // round trip, plus a resend's worth of slack) to arrive before the client does.
    if (cl.has_next && !cl.presubscribed) {
      const double lookahead = cl.speed * (3.0 * (o_.latency + o_.jitter) + 2.0 * o_.tick) + 1.0;
      if (length(cl.waypoint - cl.pos) <= lookahead) presubscribe(cl, c);
    }
  }
  void presubscribe(Client& cl, std::uint32_t c) {
    cl.presubscribed = true;
    cl.wanted = set_union(cl.wanted, graph_.nodes[cl.next].pvs_n);
    if (!contains(cl.held, cl.next)) ask_node(cl, c, cl.node);
    subscribe_missing(cl, c, graph_.nodes[cl.next].pvs_n);
  }

  // --- the tick: move, check, publish --------------------------------------------------------
  void on_tick(std::uint64_t k) {
    std::vector<std::uint32_t> active;
    for (std::uint32_t c = 0; c < o_.clients; ++c) {
      Client& cl = clients_[c];
      if (cl.phase != Phase::active) continue;
      move(cl, c);
      active.push_back(c);
      ++r_.active_client_ticks;
      const NavigationNode& node = graph_.nodes[cl.node];
      if (!contains(cl.held, cl.node)) ++r_.render_violations;
      if (!ring_contains(node.coords, cl.pos, 1e-6)) ++r_.outside_node;
      r_.listened_channels.push_back(static_cast<double>(subs_[c].size()));
      digest_ = hash_mix(hash_mix(digest_, (k << 20) ^ c), hash_mix(cl.node, hash_mix(std::bit_cast<std::uint64_t>(cl.pos.x),
                                                                   std::bit_cast<std::uint64_t>(cl.pos.y))));
    }
    if (k % o_.check_stride == 0 && los_ && active.size() > 1) check(k, active);
    for (std::uint32_t c : active) {
      Client& cl = clients_[c];
      Message m = make(MessageKind::update);
      m.client = c;
      m.channel = cl.node;
      m.request = k;
      m.position = cl.pos;
      m.bytes = kHeaderBytes + kPoseBytes;
      // The uplink message counts for every policy (each would send it).
      for (std::size_t p = kBroadcast; p < r_.policies.size(); ++p) count(p, 1, m.bytes, k);
      if (!send(m, true)) {
        const auto it = expected_.find(key(c, k));
        if (it != expected_.end()) {
          for (PolicyTraffic& p : r_.policies) p.lost_updates += it->second.size();
          expected_.erase(it);
        }
      }
    }
    r_.digest = digest_;
  }
  static std::uint64_t key(std::uint32_t client, std::uint64_t tick) { return (tick << 32) | client; }

  void check(std::uint64_t k, const std::vector<std::uint32_t>& active) {
    std::vector<Vec3> eyes;
    for (std::uint32_t c : active) eyes.push_back({clients_[c].pos.x, clients_[c].pos.y, graph_.options.eye_height});
    const auto start = std::chrono::steady_clock::now();
    const auto pairs = los_(eyes);
    r_.line_of_sight_seconds += seconds_since(start);
    ++r_.checked_ticks;
    checked_tick_[k] = 1;
    r_.pairs_checked += active.size() * (active.size() - 1) / 2;
    for (const auto& [i, j] : pairs) {
      const std::uint32_t a = active[i], b = active[j];
      ++r_.visible_pairs;
      const Client &ca = clients_[a], &cb = clients_[b];
      auto violation = [&](std::size_t policy) {
        PolicyTraffic& p = r_.policies[policy];
        ++p.grouping_violations;
        if (p.first_violations.size() < kExamples) p.first_violations.push_back({k, a, b, ca.pos, cb.pos, ca.node, cb.node});
      };
      if (!contains(subs_[a], cb.node) || !contains(subs_[b], ca.node)) {
        violation(kVbaoi);
        violation(kFiltered);  // the same channels
      }
      if (!adjacent_or_same(ca.node, cb.node)) violation(kNeighbours);
      const double d = length(ca.pos - cb.pos);
      for (std::size_t p = kFirstCircular; p < r_.policies.size(); ++p)
        if (d > r_.policies[p].radius) violation(p);
      for (PolicyTraffic& p : r_.policies) p.visible_updates += 2;
      expected_[key(b, k)].push_back(a);
      expected_[key(a, k)].push_back(b);
    }
  }

  // --- the server --------------------------------------------------------------------------
  void reply(const Message& asked, Message m) {
    m.client = asked.client;
    m.request = asked.request;
    send(std::move(m), false);
  }
  void on_server(const Message& m) {
    switch (m.kind) {
      case MessageKind::join_request: {
        const std::int64_t node = locate_node(graph_, m.position, -1, 1e-6);
        if (node < 0) return;  // cannot happen: clients start inside a node
        if (!known_[m.client]) admit(m.client, m.position, static_cast<NodeId>(node));  // not on a resent request
        Message r = make(MessageKind::join_reply);
        r.channel = static_cast<std::uint32_t>(node);
        r.bytes = kHeaderBytes + 4 + 4 + 8 * graph_.nodes[static_cast<std::size_t>(node)].coords.size();
        reply(m, r);
        break;
      }
      case MessageKind::node_request: {
        // The node and its SNs the client lacks, and the geometry of the buildings in their PVSo
        // that no node it holds already brought (differential, Fig. 5.7).
        std::vector<std::uint32_t> nodes = graph_.nodes[m.channel].neighbours;
        insert_sorted(nodes, m.channel);
        Message r = make(MessageKind::node_reply);
        r.ids = set_minus(nodes, m.held);
        std::vector<std::uint32_t> had, need;
        for (std::uint32_t n : m.held) had = set_union(had, graph_.nodes[n].pvs_o);
        for (std::uint32_t n : r.ids) need = set_union(need, graph_.nodes[n].pvs_o);
        r.bytes = kHeaderBytes + 4;
        for (std::uint32_t n : r.ids) r.bytes += node_data_bytes(graph_.nodes[n]);
        for (std::uint32_t b : set_minus(need, had)) r.bytes += building_bytes(scene_.buildings[building_index_.at(b)]);
        reply(m, r);
        break;
      }
      case MessageKind::subscribe:
      case MessageKind::unsubscribe: {
        for (std::uint32_t ch : m.ids) {
          if (m.kind == MessageKind::subscribe) {
            insert_sorted(subs_[m.client], ch);
            insert_sorted(members_[ch], m.client);
          } else {
            erase_sorted(subs_[m.client], ch);
            erase_sorted(members_[ch], m.client);
          }
        }
        Message r = make(MessageKind::ack);
        r.bytes = kHeaderBytes;
        reply(m, r);
        break;
      }
      case MessageKind::update: route_update(m); break;
      case MessageKind::welcome:
      case MessageKind::leave: {
        const std::size_t listeners = members_[m.channel].size() - (contains(members_[m.channel], m.client) ? 1 : 0);
        r_.messages_by_kind[static_cast<std::size_t>(m.kind)] += listeners;
        r_.bytes_by_kind[static_cast<std::size_t>(m.kind)] += listeners * m.bytes;
        count_channels(listeners, listeners * m.bytes, tick_index(now_));
        if (m.kind == MessageKind::welcome) {
          move_known_position(m.client, m.position);
          place(m.client, m.channel);
        }
        break;
      }
      default: break;
    }
  }

  void route_update(const Message& m) {
    const std::uint64_t k = m.request;
    const std::uint32_t y = m.client;
    place(y, m.channel);
    // Each policy's deliveries of this update, also counted against the limit when its tick was checked.
    auto deliver = [&](std::size_t policy, std::size_t n) {
      r_.policies[policy].update_deliveries += n;
      if (k < checked_tick_.size() && checked_tick_[k]) r_.policies[policy].checked_update_deliveries += n;
    };
    // VbAoI: the listeners of the update's channel.
    const auto& listeners = members_[m.channel];
    const std::size_t vbaoi = listeners.size() - (contains(listeners, y) ? 1 : 0);
    count(kVbaoi, vbaoi, vbaoi * m.bytes, k);
    r_.messages_by_kind[static_cast<std::size_t>(MessageKind::update)] += vbaoi;
    r_.bytes_by_kind[static_cast<std::size_t>(MessageKind::update)] += vbaoi * m.bytes;
    deliver(kVbaoi, vbaoi);
    // VbAoI filtered: those of the listeners that the sight filter cannot prove blind to y.
    passed_.clear();
    for (std::uint32_t x : listeners)
      if (x != y && may_see(x, m.position, k)) passed_.push_back(x);
    count(kFiltered, passed_.size(), passed_.size() * m.bytes, k);
    deliver(kFiltered, passed_.size());
    // Broadcast: every other client the server knows.
    const std::size_t everyone = known_count_ - (known_[y] ? 1 : 0);
    count(kBroadcast, everyone, everyone * m.bytes, k);
    deliver(kBroadcast, everyone);
    // Neighbours: every other client the server places in the update's node or one of its SNs.
    std::size_t near = 0;
    for (NodeId n : graph_.nodes[m.channel].neighbours) near += clients_in_[n];
    near += clients_in_[m.channel] - 1;  // y itself was placed there on arrival
    count(kNeighbours, near, near * m.bytes, k);
    deliver(kNeighbours, near);
    // Circular: every other client last known within R of the update's position.
    for (std::size_t p = kFirstCircular; p < r_.policies.size(); ++p) {
      const std::size_t n = within(m.position, r_.policies[p].radius, y);
      count(p, n, n * m.bytes, k);
      deliver(p, n);
    }
    const auto it = expected_.find(key(y, k));
    if (it != expected_.end()) {
      for (std::uint32_t x : it->second) {
        const bool lost = hashed_uniform(o_.seed ^ kNetworkStream, key(y, k), 3, x) < o_.loss;
        auto tally = [&](PolicyTraffic& p, bool routed) {
          if (!routed) ++p.missed_updates;
          else if (lost) ++p.lost_updates;
        };
        tally(r_.policies[kVbaoi], contains(listeners, x));
        tally(r_.policies[kFiltered], contains(passed_, x));
        tally(r_.policies[kBroadcast], known_[x] != 0);
        tally(r_.policies[kNeighbours], known_[x] != 0 && adjacent_or_same(server_node_[x], m.channel));
        for (std::size_t p = kFirstCircular; p < r_.policies.size(); ++p)
          tally(r_.policies[p], length(last_pos_[x] - m.position) <= r_.policies[p].radius);
      }
      expected_.erase(it);
    }
    move_known_position(y, m.position);
    if (update_tick_[y] == kNoTick || k > update_tick_[y]) {
      update_tick_[y] = k;
      update_pos_[y] = m.position;
    }
  }

  // Whether listener x may see an eye at `from` at tick k, for all the server knows: x stands
  // within speed_max x tick x |k - k_x| of the position its latest update (of tick k_x) gave; a
  // listener that has sent no update yet is not filtered.
  bool may_see(std::uint32_t x, Vec2 from, std::uint64_t k) {
    if (update_tick_[x] == kNoTick) return true;
    const double ticks = static_cast<double>(k > update_tick_[x] ? k - update_tick_[x] : update_tick_[x] - k);
    const double walked = o_.speed_max * o_.tick * ticks * (1.0 + 1e-9) + 1e-9;
    return !sight_.hidden(from, update_pos_[x], walked);
  }

  // The server learns of a client from its join request; from then on every policy counts it.
  void admit(std::uint32_t c, Vec2 position, NodeId node) {
    known_[c] = 1;
    ++known_count_;
    server_node_[c] = node;
    ++clients_in_[node];
    move_known_position(c, position);
  }
  // The node the server last heard a client in (join, welcome, or an update's channel): what the
  // neighbours baseline routes by.
  void place(std::uint32_t c, NodeId node) {
    if (server_node_[c] == node) return;
    --clients_in_[server_node_[c]];
    server_node_[c] = node;
    ++clients_in_[node];
  }
  bool adjacent_or_same(NodeId a, NodeId b) const {
    return a == b || contains(graph_.nodes[a].neighbours, b);
  }

  // The server's last known positions, bucketed on a grid of the largest radius.
  std::uint64_t grid_cell(Vec2 p) const {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x / grid_size_));
    const auto iy = static_cast<std::int64_t>(std::floor(p.y / grid_size_));
    return (static_cast<std::uint64_t>(ix) << 32) ^ static_cast<std::uint32_t>(iy);
  }
  void move_known_position(std::uint32_t c, Vec2 p) {
    // Every key is a valid cell (cell (-1, -1) hashes to ~0), so "not yet placed" is its own state.
    const std::uint64_t cell = grid_cell(p);
    if (cell != cell_of_[c]) {
      if (cell_of_[c]) erase_sorted(grid_[*cell_of_[c]], c);
      insert_sorted(grid_[cell], c);
      cell_of_[c] = cell;
    }
    last_pos_[c] = p;
  }
  std::size_t within(Vec2 p, double radius, std::uint32_t self) const {
    std::size_t n = 0;
    const auto ix = static_cast<std::int64_t>(std::floor(p.x / grid_size_));
    const auto iy = static_cast<std::int64_t>(std::floor(p.y / grid_size_));
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = grid_.find((static_cast<std::uint64_t>(ix + dx) << 32) ^ static_cast<std::uint32_t>(iy + dy));
        if (it == grid_.end()) continue;
        for (std::uint32_t c : it->second)
          if (c != self && length(last_pos_[c] - p) <= radius) ++n;
      }
    return n;
  }

  const Scene& scene_;
  const NavigationGraph& graph_;
  const SimulationOptions& o_;
  const LineOfSight& los_;
  SightFilter sight_;
  SimulationResult r_;
  Micros tick_ = 0, bound_ = 0, now_ = 0;
  std::uint64_t ticks_ = 0, seq_ = 0, message_id_ = 0, next_request_ = 1, digest_ = 0;
  std::priority_queue<Event, std::vector<Event>, Later> events_;
  std::vector<Client> clients_;
  std::unordered_map<std::uint32_t, Micros> link_up_, link_down_;
  std::unordered_map<ObjectId, std::uint32_t> building_index_;
  // Server state.
  std::vector<std::vector<std::uint32_t>> subs_;     // per client: its channels
  std::vector<std::vector<std::uint32_t>> members_;  // per channel: its listeners
  std::vector<char> known_;
  std::vector<NodeId> server_node_;
  std::vector<std::size_t> clients_in_;  // per node: clients the server places there
  std::size_t known_count_ = 0;
  std::vector<Vec2> last_pos_;
  // The sight filter's view of each client: the position and tick of its latest update.
  static constexpr std::uint64_t kNoTick = ~std::uint64_t{0};
  std::vector<Vec2> update_pos_;
  std::vector<std::uint64_t> update_tick_;
  std::vector<std::uint32_t> passed_;  // the update being routed: listeners the filter passed
  std::vector<std::optional<std::uint64_t>> cell_of_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid_;
  double grid_size_ = 1.0;
  std::vector<char> checked_tick_;  // by tick: pairs were checked (the limit is known there)
  // Observers each checked tick's update must reach, by (client, tick).
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> expected_;
};

}  // namespace

std::string_view message_kind_name(MessageKind kind) {
  static constexpr std::string_view names[kMessageKinds] = {"join_request", "join_reply", "node_request", "node_reply",
                                                            "subscribe",    "unsubscribe", "ack",         "update",
                                                            "welcome",      "leave"};
  return names[static_cast<std::size_t>(kind)];
}

void validate(const SimulationOptions& o) {
  auto fail = [](const std::string& field, const std::string& why) {
    throw std::invalid_argument("vbaoi simulation: " + field + " " + why);
  };
  auto finite_in = [&](const char* field, double v, double lo, double hi) {
    if (!std::isfinite(v) || v < lo || v > hi)
      fail(field, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], is " + std::to_string(v));
  };
  if (o.clients < 1 || o.clients > 100'000) fail("clients", "must be in [1, 100000], is " + std::to_string(o.clients));
  finite_in("tick", o.tick, 1e-3, 10.0);
  finite_in("duration", o.duration, o.tick, 86'400.0);
  if (o.duration / o.tick > 1e6) fail("duration", "needs more than 1,000,000 ticks");
  finite_in("join_window", o.join_window, 0.0, o.duration);
  finite_in("speed_min", o.speed_min, 0.0, 100.0);
  finite_in("speed_max", o.speed_max, o.speed_min, 100.0);
  finite_in("latency", o.latency, 0.0, 10.0);
  finite_in("jitter", o.jitter, 0.0, 10.0);
  finite_in("loss", o.loss, 0.0, 0.9);
  finite_in("retry_timeout", o.retry_timeout, 1e-3, 60.0);
  if (o.retry_timeout <= 2.0 * (o.latency + o.jitter))
    fail("retry_timeout", "must exceed a round trip (2 x (latency + jitter))");
  for (double r : o.circular_radii) finite_in("circular_radii", r, 0.0, 1e6);
  if (o.check_stride < 1) fail("check_stride", "must be at least 1");
}

SimulationResult simulate(const Scene& scene, const NavigationGraph& graph, const SimulationOptions& options,
                          const LineOfSight& line_of_sight) {
  validate(options);
  if (graph.nodes.empty()) throw std::invalid_argument("vbaoi simulation: the navigation graph has no nodes");
  return Simulation(scene, graph, options, line_of_sight).run();
}

}  // namespace cullcheck::vbaoi
