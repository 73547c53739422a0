#pragma once
/// The gateway as a Sparkplug B 3.0 edge node (docs/sparkplug.md): every exchange a
/// device named after it, its tags the device's metrics. NBIRTH with the node's counters and
/// `Node Control/Rebirth`, DBIRTH per device with every tag (name, alias, datatype, value,
/// properties), DDATA by exception with the changed tags by alias, DDEATH when a consumed
/// exchange goes stale or mismatches and DBIRTH again at its first good datagram; NDEATH is the
/// connection's will (next_will(), a new bdSeq for every connection made). A host's NCMD
/// `Node Control/Rebirth` brings every birth again, at most one rebirth in progress and one
/// pending (rebirth_hold); its DCMD to a produced exchange's device is one write, decoded into
/// a WriteRequest, and its echo is the DDATA of the datagram that carried it; a DCMD while the
/// node is not born is refused (`offline`). With a primary host, births wait for its STATE to
/// say online, and after an NDEATH for the broker's acknowledgement of it.
///
/// No message goes out that the broker would refuse (over its Maximum Packet Size, or
/// `max_packet_bytes`): `seq` counts only what was published, and a device (or the node) whose
/// birth cannot be published is not born, so nothing else of it is sent.
///
/// It needs an MQTT connection of its own (its will is the NDEATH), session-bound: what was
/// queued for one connection is dropped when it goes, since seq and aliases start again with
/// each birth.
///
/// Threading: the loop only.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/adapters/sparkplug/payload.hpp"
#include "eip2mqtt/app/history/history_sink.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_stats.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

struct SparkplugOptions {
    std::string group_id;
    std::string edge_node_id;
    std::string primary_host_id;  ///< empty: publish without waiting for a host
    int qos = 0;                  ///< births and data; NDEATH is QoS 1
    /// The largest message to publish, in bytes of its PUBLISH packet, below the broker's own
    /// Maximum Packet Size (0: the broker's alone); for brokers that do not announce theirs.
    std::size_t max_packet_bytes = 0;
};

/// How long a rebirth stays in progress: requests meanwhile (NCMD, the primary host back
/// online) make one pending rebirth, done when it ends. A flood of requests costs one rebirth
/// a second, not one each.
inline constexpr std::chrono::seconds rebirth_hold{1};

/// Set in every ack_token the node gives its own publications, never in a journal entry's id
/// (SQLite row ids stay below 2^63): one acknowledgement handler tells them apart.
inline constexpr std::uint64_t sparkplug_own_token = std::uint64_t{1} << 63;

/// The options of `config`'s `sparkplug:` section.
SparkplugOptions sparkplug_options(const core::config::Config& config);

class SparkplugNode final : public Northbound, public history::HistorySink {
public:
    /// `mqtt` (the node's own connection), `writes` and `clock` (the payloads' timestamps)
    /// must outlive the node.
    SparkplugNode(SparkplugOptions options, adapters::mqtt::Publisher& mqtt, WriteHandler& writes,
                  const core::Clock& clock);

    /// The NDEATH for the next CONNECT's will; the NBIRTH that follows that connection carries
    /// the same bdSeq. Each connection made takes the next bdSeq (0-255, then 0 again); an
    /// attempt that failed leaves it as it was.
    adapters::mqtt::Message next_will();
    /// A pair's leader opens the one edge node's session (docs/redundancy.md): the next will
    /// takes a bdSeq other than that of the pair's last session, one more than `heard` (the
    /// last one this unit read in a leader record; core/redundancy/bd_seq.hpp).
    void begin_session(std::optional<std::uint8_t> heard);
    /// A pair's leader stepped down, its connection's session ended (Client::end_session):
    /// nothing more is published until the next connection's births.
    void end_session();
    /// The bdSeq of the will made for the current session (its connection, or the attempt
    /// under way); nullopt before the first will and after end_session().
    std::optional<std::uint8_t> session_bd_seq() const {
        return session_open_ ? std::optional<std::uint8_t>(bd_seq_) : std::nullopt;
    }
    /// The connection is up, to a broker taking packets of up to `max_packet_bytes`
    /// (Client::max_packet_size()): births now, or once the primary host says it is online.
    void on_connected(std::size_t max_packet_bytes = adapters::mqtt::max_mqtt_packet_bytes);
    /// NCMD, DCMD or the primary host's STATE; anything else is ignored.
    void on_message(const adapters::mqtt::Incoming& message);
    /// The broker acknowledged the publication that carried `ack_token`. True when the token
    /// is the node's own (its NDEATH); false when it is another owner's, the journal entry of a
    /// historical DDATA (replay()): the node's connection carries both.
    bool on_acknowledged(std::uint64_t ack_token);
    /// The gateway's tick: a pending rebirth whose time has come, and the summaries of
    /// throttled logs.
    void tick(core::MonoTime now);

    void exchanges_changed(const ExchangeSet& running,
                           std::span<const std::string> retired_topics) override;
    void tag_samples(const SampleBatch& batch) override;
    void consumed_status(const ConsumedStatus& status) override;
    void produced_status(const core::plan::ExchangePlan& exchange,
                         const ProducedStatus& status) override;
    void exchange_state(const core::plan::ExchangePlan& exchange,
                        core::exchange::ConsumeState state) override;
    // write_result: Sparkplug has no answer to a command; an accepted write shows as its
    // echo, a refused one in the log and the counters (the WriteDispatcher's).
    void gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime) override;
    /// Store and forward's history as DDATA with `is_historical` on every metric, by alias: for
    /// a device born now, and good samples only (bad data is a DDEATH in this convention); the
    /// DDATA carries `ack_token`, which the node's connection hands back once it is sent.
    bool replay(const SampleBatch& batch, std::uint64_t ack_token) override;

    bool born() const { return born_; }
    std::uint8_t bd_seq() const { return bd_seq_; }
    const SparkplugStats& stats() const { return stats_; }
    /// Every counter at its largest and every state at its longest, so that the next NBIRTH is
    /// as large as it can grow (sparkplug_birth_sizes).
    void widen_node_metrics_for_sizing();

private:
    struct Device {
        const core::plan::ExchangePlan* plan = nullptr;
        bool produced = false;         ///< writable by DCMD, its plan the ExchangeWrite's handle
        std::uint64_t alias_base = 0;  ///< a tag's alias is alias_base + its index
        std::vector<std::optional<core::plan::Value>> values;
        std::vector<std::int64_t> timestamps;
        std::size_t known = 0;              ///< values that are set
        bool up = false;                    ///< consumed: state ok; produced: every value known
        bool born = false;                  ///< DBIRTH sent since the last NBIRTH
        bool birth_refused_logged = false;  ///< since its last DBIRTH published
        std::string birth_topic, data_topic, death_topic;
    };
    /// A node metric: the gateway's counters, each exchange's state and counters.
    struct NodeMetric {
        std::string name;
        adapters::sparkplug::DataType type;
        adapters::sparkplug::MetricValue value;
        bool changed = false;  ///< since the last NBIRTH or NDATA
    };

    bool may_publish() const {
        return connected_ && (options_.primary_host_id.empty() || host_online_);
    }
    /// NDEATH with the current bdSeq.
    adapters::mqtt::Message death_message() const;
    /// A rebirth asked for (NCMD, the primary host online): now, or pending until the one in
    /// progress ends and the broker acknowledged the last NDEATH.
    void request_birth();
    bool birth_may_start() const;
    /// NBIRTH, then DBIRTH for every device that is up.
    void birth();
    void device_birth(Device& device);
    void device_death(Device& device);
    /// Publishes with the next seq, the message carrying `ack_token` (0: none); false, with
    /// nothing published and seq unchanged, when the message is over the largest packet the
    /// broker takes.
    bool publish(const std::string& topic, adapters::sparkplug::Payload& payload,
                 std::uint64_t ack_token = 0);
    /// A birth that publish() refused: counted, logged once for each device or the node.
    void birth_refused(const std::string& topic, bool& logged);
    void data_refused();
    /// SparkplugStats into the node metrics, for the next NDATA.
    void publish_counters();
    /// DDATA of `batch`'s samples by alias, live or historical (with the journal entry's
    /// token); false when it was refused for its size (counted in data_refused).
    bool publish_data(const Device& device, const SampleBatch& batch, bool historical,
                      std::uint64_t ack_token = 0);
    std::string node_topic(std::string_view type) const;
    std::size_t node_metric(const std::string& name, adapters::sparkplug::DataType type);
    void set_node_metric(std::size_t index, adapters::sparkplug::MetricValue value);
    void on_node_command(const adapters::mqtt::Incoming& message);
    /// A DCMD for `device` (nullptr: no exchange of that name): one WriteRequest, refused or not.
    void on_device_command(const adapters::mqtt::Incoming& message, Device* device);
    void on_state(const adapters::mqtt::Incoming& message);
    /// The primary host's STATE changed: births (request_birth), or the NDEATH.
    void host_online(bool online);
    /// NDEATH now, on this connection (the host went offline): no birth before the broker
    /// acknowledges it.
    void publish_death();

    SparkplugOptions options_;
    adapters::mqtt::Publisher& mqtt_;
    WriteHandler& writes_;
    const core::Clock& clock_;
    std::string ncmd_topic_, dcmd_prefix_, state_topic_;

    std::vector<Device> devices_;
    std::unordered_map<const core::plan::ExchangePlan*, std::size_t> device_of_plan_;
    std::unordered_map<std::string, std::size_t> device_of_name_;
    std::vector<NodeMetric> node_metrics_;
    std::unordered_map<std::string, std::size_t> node_metric_of_name_;

    bool connected_ = false;
    bool host_online_ = false;
    std::int64_t host_state_timestamp_ = 0;  ///< of the last STATE taken: older ones are stale
    bool born_ = false;                      ///< NBIRTH sent on this connection, host online
    std::uint8_t bd_seq_ = 0;                ///< of the current connection's will
    std::uint8_t next_bd_seq_ = 0;
    bool will_connected_ = true;  ///< the last will's CONNECT made a connection
    bool session_open_ = false;   ///< a will was made since the last end_session()
    std::uint8_t seq_ = 0;        ///< of the next message to publish
    std::size_t max_packet_bytes_ = adapters::mqtt::max_mqtt_packet_bytes;
    std::size_t last_packet_bytes_ = 0;  ///< the size of the last message publish() was given
    bool node_birth_refused_logged_ = false;
    /// The NDEATH said on this connection and not yet acknowledged: no birth before it is.
    std::uint64_t death_unacknowledged_ = 0;
    core::MonoTime death_deadline_{};  ///< births go on without the acknowledgement then
    std::uint64_t next_ack_token_ = 0;
    bool rebirth_pending_ = false;
    core::MonoTime now_{};               ///< of the last tick
    core::MonoTime birth_hold_until_{};  ///< a rebirth is in progress until then
    SparkplugStats stats_;
    adapters::sparkplug::Payload payload_;  ///< filled again for every message
    adapters::mqtt::Message message_;
    core::ThrottledLog command_log_;  ///< NCMD and STATE that cannot be read
    core::ThrottledLog rebirth_log_;  ///< NCMD rebirth requests
    core::ThrottledLog state_log_;    ///< the primary host's STATE changes
    core::ThrottledLog refused_log_;  ///< DCMD refused while the node is not born
};

}  // namespace eip2mqtt::app::northbound::sparkplug
