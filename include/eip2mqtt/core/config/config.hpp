#pragma once
/// The configuration model: plain structs as the YAML adapter fills them, with the mark of every
/// key they came from so that semantic checks can point at the offending line and column.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "eip2mqtt/core/config/diagnostic.hpp"
#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/net/subnet.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::core::config {

/// Where each key of a mapping was written. `node` is the mapping itself.
struct Marks {
    Mark node;
    /// Each key written, with its mark, in document order. A mapping has a handful of keys, so
    /// a flat vector: one heap block where a std::map took one per key (100,000 tags: see
    /// docs/decisions/0001-configurations-of-100000-tags.md).
    std::vector<std::pair<std::string, Mark>> keys;

    /// The key's mark, or the node's when the key was not written.
    const Mark& of(std::string_view key) const;
    bool contains(std::string_view key) const;
    /// Records `key` at `at`; false, and nothing recorded, when the key already was.
    bool add(std::string_view key, const Mark& at);
};

struct TagConfig {
    plan::TagSpec spec;
    Marks marks;
};

struct ExchangeConfig {
    plan::ExchangeSpec spec;      ///< spec.tags is left empty: see `tags`
    std::vector<TagConfig> tags;  ///< `tags:` entries, then the point-list rows
    Marks marks;
};

struct GatewaySection {
    std::string id = "eip2mqtt";
    std::string state_dir = "/var/lib/eip2mqtt";
    std::string log_level = "info";
    /// `timestamp` and `clock_tolerance_ms`: what a consumed exchange takes unless it says.
    plan::ExchangeDefaults exchange_defaults;
    /// The farthest level of `location`: what an exchange or a tag does not say.
    plan::Location location;
    Marks marks;
};

struct TlsSection {
    std::string ca_file;
    std::string cert_file;
    std::string key_file;
    bool verify = true;
};

/// `mqtt.payload`, the shape of data messages (docs/mqtt-api.md, "Payload profiles"): json
/// (`{"value","timestamp","quality"}`), raw (the value as JSON), value (the value as text: a
/// string bare), umh (`{"value","timestamp_ms"}`), kepware (`{"timestamp","values":[{"id","v",
/// "q","t"}]}`, which publishes `_values` as well).
enum class PayloadFormat : std::uint8_t { json, raw, value, umh, kepware };

inline constexpr auto payload_format_names =
    enum_names<PayloadFormat>("json", "raw", "value", "umh", "kepware");

/// `mqtt.store_and_forward`: while the broker is out of reach, what the exchanges
/// bring is journaled on disk, then replayed on `{exchange}/_history` once it is back.
struct StoreAndForwardSection {
    bool enabled = false;
    std::uint64_t max_mb = 256;                      ///< the journal's bound on disk
    std::uint32_t replay_rate = 2000;                ///< history messages per second at most
    std::chrono::milliseconds fsync_interval{1000};  ///< power loss loses at most this much
    Marks marks;

    friend bool operator==(const StoreAndForwardSection& a, const StoreAndForwardSection& b) {
        return a.enabled == b.enabled && a.max_mb == b.max_mb && a.replay_rate == b.replay_rate &&
               a.fsync_interval == b.fsync_interval;
    }
};

/// `mqtt.properties`: what MQTT 5 user properties every data message carries.
enum class MessageProperty : std::uint8_t { unit, quality, source_time, exchange, producer };
inline constexpr auto message_property_names =
    enum_names<MessageProperty>("unit", "quality", "source_time", "exchange", "producer");

struct MqttSection {
    /// A connection's name (`mqtt` may list several, docs/configuration.md): its label in logs,
    /// metrics, `/readyz` and the status page, and its journal's file name. Required in a list
    /// of two or more; a lone connection's default is "mqtt".
    std::string name;
    /// Whether writes are taken from this broker's clients (and answered on it); unset: the
    /// first connection only.
    std::optional<bool> writes;
    /// `url`: one broker, or several tried in turn (the first at start, the next after each
    /// lost connection or failed attempt). Never empty once read.
    std::vector<std::string> urls{"tcp://localhost:1883"};
    int version = 5;        ///< 5 or 3 (3.1.1)
    std::string client_id;  ///< default: eip2mqtt-{gateway.id}
    std::string username;
    std::string password_file;
    std::optional<TlsSection> tls;
    std::string base_topic = "eip2mqtt";
    /// Each tag's topic (plan::TopicTemplate); the default is {base}/{exchange}/{tag}.
    std::string topic_template{plan::default_topic_template};
    int qos = 1;
    bool retain = true;
    PayloadFormat payload = PayloadFormat::json;
    std::size_t buffer_max_messages = 100000;
    bool batch = false;
    /// With batch: `_values` go before the tag topics whenever both wait (for a historian that
    /// needs every sample more than the tag tree needs every intermediate value, which
    /// coalesces: latest value wins). Off: the two are served in turn.
    bool batch_first = false;
    /// Whether a write's MQTT 5 response topic may lie under base_topic outside a `set` topic.
    /// Off: a client that may only write `…/set` cannot make the gateway publish on its own
    /// topics (a tag, `_gateway/…/state`).
    bool allow_response_topics_under_base = false;
    /// MQTT 5 metadata (docs/mqtt-api.md): the content type and payload format indicator of
    /// every JSON and text message, user properties of data messages, the expiry of live values
    /// (0: none) and topic aliases; MQTT 3.1.1 has none of them.
    bool describe_payloads = true;
    std::vector<MessageProperty> properties;
    std::chrono::seconds message_expiry{0};
    bool topic_aliases = false;
    std::chrono::seconds keepalive{30};
    /// MQTT 5 session expiry: 0 starts clean every time; more keeps the session (and the QoS 1
    /// writes sent to it) on the broker while the gateway is away, up to this long.
    std::chrono::seconds session_expiry{0};
    std::chrono::seconds metrics_interval{10};
    StoreAndForwardSection store_and_forward;
    Marks marks;
};

struct MulticastGroup {
    std::string group;
    std::string interface;  ///< interface name or IPv4 address; empty: the default

    friend bool operator==(const MulticastGroup&, const MulticastGroup&) = default;
};

/// `eip.commands`: the responder of the command protocol on UDP 7937 (docs/protocol.md §9).
struct CommandsSection {
    bool enabled = false;  ///< nothing listens on the port unless asked
    std::uint16_t port = 7937;
    /// The requesters answered (an address filter: it authenticates no one). Not written: the
    /// subnets of `eip.bind`'s interfaces (resolved at start, when the interfaces are known);
    /// written empty (`allow: []`): nobody.
    std::optional<std::vector<net::Subnet>> allow;
    /// Requesters answered in full without proving their address (§9.7): tools that cannot
    /// carry a token. A forged source inside them is answered in full, and may write.
    std::vector<net::Subnet> trusted;
    bool writes = false;  ///< Write and Masked Write; off: answered `not_permitted`
    std::uint32_t max_requests_per_s = 100;  ///< beyond: dropped unanswered, and counted
    /// The same for each requester address, so that one cannot spend every other's share.
    std::uint32_t max_requests_per_s_per_source = 20;
    Marks marks;

    friend bool operator==(const CommandsSection& a, const CommandsSection& b) {
        return a.enabled == b.enabled && a.port == b.port && a.allow == b.allow &&
               a.trusted == b.trusted && a.writes == b.writes &&
               a.max_requests_per_s == b.max_requests_per_s &&
               a.max_requests_per_s_per_source == b.max_requests_per_s_per_source;
    }
};

struct EipSection {
    std::string bind = "0.0.0.0";
    std::uint16_t port = 18246;
    std::vector<MulticastGroup> multicast;
    int multicast_ttl = 1;  ///< TTL of produced multicast datagrams
    std::string
        multicast_interface;  ///< IPv4 address of the interface produced multicast leaves by
    /// The link's capacity in Mbit/s: `check` warns of produced traffic over half of it, and
    /// refuses more than all of it.
    double link_mbps = 100;
    CommandsSection commands;
    Marks marks;
};

/// The largest `eip.link_mbps` accepted: 400 Gbit/s, the fastest Ethernet sold.
inline constexpr double max_link_mbps = 400000;

/// `metrics.auth`: HTTP basic authentication on the listener (/healthz and /readyz excepted).
struct MetricsAuth {
    std::string username;
    std::string password_file;  ///< a systemd credential's name, or a path

    friend bool operator==(const MetricsAuth&, const MetricsAuth&) = default;
};

/// `metrics.tls`: the listener speaks HTTPS with this certificate and key (PEM files).
struct MetricsTls {
    std::string cert;  ///< the certificate, and any intermediates after it
    std::string key;

    friend bool operator==(const MetricsTls&, const MetricsTls&) = default;
};

struct MetricsSection {
    std::string listen;  ///< host:port of the Prometheus endpoint; empty: off
    std::optional<MetricsAuth> auth;
    std::optional<MetricsTls> tls;
    Marks marks;
};

/// `sparkplug:`: the gateway as a Sparkplug B edge node, beside the JSON tree.
struct SparkplugSection {
    std::string group_id;      ///< empty: Sparkplug is off
    std::string edge_node_id;  ///< default: sparkplug_node_id()
    std::string primary_host_id;
    bool uns = true;  ///< keep the JSON topic tree as well
    /// Always 0: Sparkplug B 3.0 sends births and data at QoS 0 (the NDEATH will at 1). The key
    /// stays so that configurations of earlier releases that set `qos: 0` still load; 1 is
    /// refused (docs/sparkplug.md, "Conformance").
    int qos = 0;
    /// The largest message the broker takes, for one that does not say (MQTT 5 CONNACK's Maximum
    /// Packet Size); 0: the broker's alone. `check` warns of a birth larger than this (or
    /// than 128 KiB when 0).
    std::size_t max_packet_bytes = 0;
    /// The `mqtt` connection (by name) whose brokers carry the edge node; empty: the first.
    std::string connection;
    Marks marks;

    bool enabled() const { return !group_id.empty(); }
};

/// `redundancy:`: two gateways, one leading and one standing by (docs/redundancy.md).
struct RedundancySection {
    std::string pair;  ///< the same on both units; empty: no pair
    /// The standby takes over this long after it last heard the leader.
    std::chrono::milliseconds takeover{2000};
    /// When both claim the lead at once, the higher wins (then the higher gateway.id).
    std::optional<int> priority;
    Marks marks;

    bool enabled() const { return !pair.empty(); }
};

/// The fewest milliseconds `redundancy.takeover_ms` takes: the lease is renewed every quarter.
inline constexpr long long min_takeover_ms = 200;
inline constexpr long long max_takeover_ms = 600000;

struct Config {
    std::string file;  ///< path it was loaded from
    GatewaySection gateway;
    /// The first (or only) MQTT connection: the gateway's main one, which the redundant pair,
    /// the metrics topic and the gateway's own state use.
    MqttSection mqtt;
    /// The connections after the first when `mqtt` is a list: each its own brokers, session,
    /// buffer, journal and topic tree, carrying the same exchanges (docs/configuration.md).
    std::vector<MqttSection> more_mqtt;
    EipSection eip;
    MetricsSection metrics;
    SparkplugSection sparkplug;
    RedundancySection redundancy;
    std::vector<ExchangeConfig> exchanges;
};

/// The Sparkplug edge node's id: `sparkplug.edge_node_id`; by default the pair's name in a
/// pair, whose two units are one edge node (docs/redundancy.md), else `gateway.id`.
inline const std::string& sparkplug_node_id(const Config& config) {
    if (!config.sparkplug.edge_node_id.empty()) return config.sparkplug.edge_node_id;
    return config.redundancy.enabled() ? config.redundancy.pair : config.gateway.id;
}

/// Every MQTT connection, the first one first: its section and its place (0: `mqtt`).
inline std::vector<const MqttSection*> mqtt_connections(const Config& config) {
    std::vector<const MqttSection*> out{&config.mqtt};
    for (const auto& more : config.more_mqtt) out.push_back(&more);
    return out;
}

/// Connection `index` of mqtt_connections(); the first when there is no such connection.
inline const MqttSection& mqtt_connection(const Config& config, std::size_t index) {
    return index == 0 || index > config.more_mqtt.size() ? config.mqtt
                                                         : config.more_mqtt[index - 1];
}

/// A connection's name: its `name`, else "mqtt".
inline std::string connection_name(const MqttSection& mqtt) {
    return mqtt.name.empty() ? "mqtt" : mqtt.name;
}

/// Whether connection `index` takes writes: its `writes`, else only the first does.
inline bool takes_writes(const MqttSection& mqtt, std::size_t index) {
    return mqtt.writes.value_or(index == 0);
}

/// The place, in mqtt_connections(), of the connection that carries Sparkplug B:
/// `sparkplug.connection` by name, else the first (validate() refuses an unknown name).
std::size_t sparkplug_connection(const Config& config);

/// Semantic checks across the whole model (tags may overlap: plan::find_overlaps): tags past
/// the end, lengths over 1400, bit addresses on non-bit types, duplicate names and (producer,
/// exchange) pairs, writable tags on consumed exchanges, min > max, topic rules, topic collisions
/// (write and result topics included), reserved words (`set`, `_…`) in tag names and exchange
/// topics, names, topics and ids that are not text a broker accepts (plan::text_problem), and
/// topics the gateway would build longer than plan::max_topic_bytes. Returns every problem found,
/// in file order.
Diagnostics validate(const Config& config);

/// Plans of every exchange of a valid configuration, in configuration order.
std::vector<plan::ExchangePlan> make_plans(const Config& config);

}  // namespace eip2mqtt::core::config
