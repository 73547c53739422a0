#pragma once
/// The gateway as a Sparkplug B 3.0 edge node (docs/sparkplug.md): every exchange a
/// device named after it, its tags the device's metrics. NBIRTH with the node's counters and
/// `Node Control/Rebirth` (no alias), DBIRTH per device with every tag (name, alias, datatype,
/// value, properties), DDATA by exception with the changed tags by alias, DDEATH when a consumed
/// exchange goes stale or mismatches and DBIRTH again at its first good datagram; NDEATH is the
/// connection's will (next_will(), a new bdSeq for every connection made, on from the last
/// process's). A host's NCMD `Node Control/Rebirth` stops DATA and brings every birth again at
/// once; requests within rebirth_hold after it share one rebirth at the hold's end. Its DCMD to
/// a produced exchange's device is one write, decoded into a WriteRequest, and its echo is the
/// DDATA of the datagram that carried it; a DCMD while the node is not born is refused
/// (`offline`). With a primary host, births wait for its STATE to say online; when it says
/// offline, the node leaves its broker (leave_broker: its NDEATH, DISCONNECT, the next broker
/// of the list) and waits there for the host again.
///
/// No message goes out that the broker would refuse (over its Maximum Packet Size, or
/// `max_packet_bytes`): `seq` counts only what was published, and a device (or the node) whose
/// birth cannot be published is not born, so nothing else of it is sent.
///
/// It needs an MQTT connection of its own (its will is the NDEATH), session-bound: what was
/// queued for one connection is dropped when it goes, since seq and aliases start again with
/// each birth.
///
/// A façade over its parts, one duty each: NodeSession (bdSeq, the connection, when births may
/// start), SeqPublisher (seq, the packet size limit), DeviceRegistry (devices, aliases, their
/// values), NodeMetrics (the node's metrics) and NodeCommands (NCMD, DCMD, the host's STATE).
/// It orders what they decide into births, data and deaths.
///
/// Threading: the loop only.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/adapters/sparkplug/payload.hpp"
#include "eip2mqtt/app/history/history_sink.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/northbound/sparkplug/device_registry.hpp"
#include "eip2mqtt/app/northbound/sparkplug/node_commands.hpp"
#include "eip2mqtt/app/northbound/sparkplug/node_metrics.hpp"
#include "eip2mqtt/app/northbound/sparkplug/node_session.hpp"
#include "eip2mqtt/app/northbound/sparkplug/seq_publisher.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_stats.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

struct SparkplugOptions {
    std::string group_id;
    std::string edge_node_id;
    std::string primary_host_id;  ///< empty: publish without waiting for a host
    /// The largest message to publish, in bytes of its PUBLISH packet, below the broker's own
    /// Maximum Packet Size (0: the broker's alone); for brokers that do not announce theirs.
    std::size_t max_packet_bytes = 0;
    /// The bdSeq of the last will before this process: the first will takes the next one.
    std::optional<std::uint8_t> last_bd_seq;
};

/// The options of `config`'s `sparkplug:` section.
SparkplugOptions sparkplug_options(const core::config::Config& config);

class SparkplugNode final : public Northbound, public history::HistorySink {
public:
    /// `mqtt` (the node's own connection), `writes` and `clock` (the payloads' timestamps)
    /// must outlive the node. `leave_broker` ends the connection's session (its will, the
    /// NDEATH, then DISCONNECT) and connects to the next broker of the list.
    SparkplugNode(SparkplugOptions options, adapters::mqtt::Publisher& mqtt, WriteHandler& writes,
                  const core::Clock& clock, std::function<void()> leave_broker);

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
    std::optional<std::uint8_t> session_bd_seq() const { return session_.session_bd_seq(); }
    /// The connection is up, to a broker taking packets of up to `max_packet_bytes`
    /// (Client::max_packet_size()): births now, or once the primary host says it is online.
    void on_connected(std::size_t max_packet_bytes = adapters::mqtt::max_mqtt_packet_bytes);
    /// NCMD, DCMD or the primary host's STATE; anything else is ignored.
    void on_message(const adapters::mqtt::Incoming& message);
    /// The gateway's tick: a waiting rebirth whose time has come, and the summaries of
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

    bool born() const { return session_.born(); }
    /// DDATA may go out, live or historical: born, and no rebirth a host asked for waits.
    bool may_send_data() const { return session_.may_send_data(); }
    std::uint8_t bd_seq() const { return session_.bd_seq(); }
    const SparkplugStats& stats() const { return stats_; }
    /// The session's state into stats().session, for whoever reads it next.
    void refresh_session();
    /// Every counter at its largest and every state at its longest, so that the next NBIRTH is
    /// as large as it can grow (sparkplug_birth_sizes).
    void widen_node_metrics_for_sizing();

private:
    /// A rebirth a host asked for: now, or when the hold after the last one ends.
    void request_birth();
    /// NBIRTH, then DBIRTH for every device that is up; `requested`: by a host (rebirth_hold).
    void birth(bool requested);
    void device_birth(Device& device);
    void device_death(Device& device);
    /// A birth that publish() refused: counted, logged once for each device or the node.
    void birth_refused(const std::string& topic, bool& logged);
    void data_refused();
    /// SparkplugStats into the node metrics, for the next NDATA.
    void publish_counters();
    /// DDATA of `batch`'s samples by alias, live or historical (with the journal entry's
    /// token); false when it was refused for its size (counted in data_refused).
    bool publish_data(Device& device, const SampleBatch& batch, bool historical,
                      std::uint64_t ack_token = 0);
    std::string node_topic(std::string_view type) const;
    /// The primary host's STATE changed: births, or the node leaves its broker.
    void host_online(bool online);

    SparkplugOptions options_;
    const core::Clock& clock_;
    NodeSession session_;
    SeqPublisher out_;
    DeviceRegistry devices_;
    NodeMetrics metrics_;
    NodeCommands commands_;
    SparkplugStats stats_;
    std::function<void()> leave_broker_;
    bool node_birth_refused_logged_ = false;
    adapters::sparkplug::Payload payload_;  ///< filled again for every message
};

}  // namespace eip2mqtt::app::northbound::sparkplug
