#pragma once
/// The runs of the Sparkplug conformance suite: the real binary as an edge node, its mqtt.url
/// two relays (mqtt_relay.hpp) in front of two Mosquittos, the suite playing the host on each
/// broker (STATE, rebirth requests, DCMD) and the plant (a consumed exchange it feeds and
/// silences, a produced one it receives). What the relays recorded becomes the NodeView the
/// checks judge, with the marks of what the suite did when.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tests/conformance/sparkplug_view.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"
#include "tests/support/paced_producer.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test::conformance {

/// `payload` (Sparkplug B bytes) with no datatype on any metric: the form the specification
/// recommends for commands.
std::string without_datatypes(const std::string& payload);

class SparkplugRun {
public:
    /// `version`: 5 or 3 (MQTT 3.1.1); `primary_host`: the node waits for `scada`.
    SparkplugRun(int version, bool primary_host);
    ~SparkplugRun();

    void start_gateway();
    /// SIGTERM, and the exit status (0 expected).
    int stop_gateway();
    /// The STATE of `scada` on broker `b`, retained as a host publishes it.
    void state(std::size_t b, bool online, std::int64_t timestamp);
    /// An NCMD `Node Control/Rebirth` true on broker `b`: with its datatype, or without.
    void rebirth(std::size_t b, bool typed);
    /// A DCMD to `setpoints` on broker `b` with `payload` (Sparkplug B bytes).
    void dcmd(std::size_t b, const std::string& payload);
    /// The plant: the consumed exchange's datagrams stop, or start again.
    void silence_plant(bool silent);
    /// The next datagram the produced exchange sends whose dint at offset 0 (SP) and real at
    /// offset 4 (SPR) satisfy `wanted`; false after 20 s.
    bool produced(const std::function<bool(std::int32_t sp, float spr)>& wanted);

    /// Waits until the node sent `count` PUBLISHes of `type` (NBIRTH...) since the start,
    /// through relay `b` (any when b > 1).
    bool sent(const std::string& type, std::size_t count, std::size_t b = 2);
    /// Waits until relay `b` saw the node SUBSCRIBE to the host's STATE `count` times.
    bool subscribed_to_state(std::size_t b, std::size_t count);
    /// Records that the suite did `what` now.
    void mark(const std::string& what);

    /// The node as the relays saw it, with the marks and the run's UTC span.
    NodeView view() const;
    /// Every Sparkplug payload the node published, for Tahu.
    std::vector<std::string> payloads() const;
    std::string output() const { return gateway_ ? gateway_->output() : std::string(); }

    /// How many PUBLISHes of `type` the node sent through relay `b` (any when b > 1).
    std::size_t count_sent(std::size_t b, const std::string& type) const;

private:
    std::vector<RelayEvent> all_events() const;

    int version_;
    TempDir dir_;
    std::vector<std::unique_ptr<Mosquitto>> brokers_;
    std::vector<std::unique_ptr<MqttRelay>> relays_;
    std::vector<std::unique_ptr<MqttRecorder>> hosts_;
    UdpClient plant_;
    UdpClient sink_;
    std::uint16_t gateway_port_;
    std::string config_path_;
    std::unique_ptr<ChildProcess> gateway_;
    std::unique_ptr<PacedProducer> producer_;
    std::map<std::string, std::chrono::steady_clock::time_point> marks_;
    std::int64_t wall_from_ms_;
};

}  // namespace eip2mqtt::test::conformance
