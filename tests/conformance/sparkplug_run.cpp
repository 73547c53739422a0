// The conformance suite's run: two brokers behind recording relays, the gateway as the edge
// node, the suite as its host and its plant.

#include "tests/conformance/sparkplug_run.hpp"

#include <signal.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::test::conformance {
namespace {

using namespace std::chrono_literals;
using core::plan::TagType;
using nlohmann::json;

std::int64_t wall_ms() {
    return std::chrono::duration_cast<std::chrono::milliseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

/// The consumed exchange `line` (A dint with a unit and a description, B real; a counter
/// changing every datagram) and the produced `setpoints` (SP dint 0-100, SPR real).
std::string exchanges(std::uint16_t sink_port) {
    return ExchangeYaml::consume("line", "10.0.0.2", 7)
               .length(8)
               .period_ms(50)
               .timeout_ms(400)
               .tag("A", "0.0", "dint", "unit: bar, description: pressure")
               .tag("B", "4.0", "real")
               .str() +
           ExchangeYaml::produce("setpoints", "10.0.0.1", 10,
                                 "127.0.0.1:" + std::to_string(sink_port))
               .length(8)
               .period_ms(100)
               .tag("SP", "0.0", "dint", "writable: true, min: 0, max: 100")
               .tag("SPR", "4.0", "real", "writable: true")
               .str();
}

}  // namespace

std::string without_datatypes(const std::string& payload) {
    SparkplugPayload proto;
    proto.ParseFromString(payload);
    for (auto& metric : *proto.mutable_metrics()) metric.clear_datatype();
    return proto.SerializeAsString();
}

SparkplugRun::SparkplugRun(int version, bool primary_host)
    : version_(version), gateway_port_(free_udp_port()), wall_from_ms_(wall_ms()) {
    std::string urls;
    for (std::size_t b = 0; b < 2; ++b) {
        brokers_.push_back(std::make_unique<Mosquitto>());
        relays_.push_back(std::make_unique<MqttRelay>(brokers_[b]->port(), b));
        hosts_.push_back(std::make_unique<MqttRecorder>(brokers_[b]->url(),
                                                        std::vector<std::string>{"spBv1.0/#"},
                                                        "host-" + std::to_string(b)));
        urls += (b == 0 ? "" : ", ") + ("\"" + relays_[b]->url() + "\"");
    }
    const std::string config = "gateway: { id: conf-gw, state_dir: " + dir_.path() +
                               "/state, log_level: debug }\n" + "mqtt:\n  url: [ " + urls +
                               " ]\n  version: " + std::to_string(version) +
                               "\n  base_topic: conf\n  metrics_interval_s: 1\n" +
                               "eip: { bind: 127.0.0.1, port: " + std::to_string(gateway_port_) +
                               " }\n" + "sparkplug: { group_id: plant1, edge_node_id: gw1" +
                               (primary_host ? ", primary_host_id: scada" : "") + " }\n" +
                               "exchanges:\n" + exchanges(sink_.port());
    config_path_ = dir_.write("gateway.yaml", config);
    producer_ = std::make_unique<PacedProducer>(
        [](std::uint64_t n) {
            return DatagramBuilder("10.0.0.2", 7, 8)
                .request_id(static_cast<std::uint16_t>(n))
                .set("0.0", TagType::dint, core::plan::Value{static_cast<std::int64_t>(n)})
                .set("4.0", TagType::real, core::plan::Value{1.5f})
                .build();
        },
        [this](const std::vector<std::byte>& d) { plant_.send_to(gateway_port_, d); }, 50ms);
}

SparkplugRun::~SparkplugRun() {
    producer_.reset();
    if (gateway_) {
        gateway_->signal(SIGKILL);
        gateway_->wait(10s);
    }
}

void SparkplugRun::start_gateway() {
    gateway_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{gateway_binary(), "run", "-c", config_path_});
}

int SparkplugRun::stop_gateway() {
    gateway_->signal(SIGTERM);
    return gateway_->wait(20s).value_or(-1);
}

void SparkplugRun::state(std::size_t b, bool online, std::int64_t timestamp) {
    hosts_.at(b)->publish("spBv1.0/STATE/scada",
                          std::string(R"({"online":)") + (online ? "true" : "false") +
                              R"(,"timestamp":)" + std::to_string(timestamp) + "}",
                          true);
}

void SparkplugRun::rebirth(std::size_t b, bool typed) {
    json metric{{"name", "Node Control/Rebirth"}, {"type", "Boolean"}, {"value", true}};
    auto payload = tahu_encode({{"timestamp", wall_ms()}, {"metrics", json::array({metric})}});
    if (!typed) payload = without_datatypes(payload);
    hosts_.at(b)->publish("spBv1.0/plant1/NCMD/gw1", payload);
}

void SparkplugRun::dcmd(std::size_t b, const std::string& payload) {
    hosts_.at(b)->publish("spBv1.0/plant1/DCMD/gw1/setpoints", payload);
}

void SparkplugRun::silence_plant(bool silent) {
    if (silent) {
        producer_->pause();
    } else {
        producer_->resume();
    }
}

bool SparkplugRun::produced(const std::function<bool(std::int32_t, float)>& wanted) {
    const auto deadline = std::chrono::steady_clock::now() + 20s;
    while (std::chrono::steady_clock::now() < deadline) {
        const auto datagram = sink_.receive(1s);
        if (!datagram || datagram->size() < 40) continue;
        std::int32_t sp = 0;
        float spr = 0;
        std::memcpy(&sp, datagram->data() + 32, 4);
        std::memcpy(&spr, datagram->data() + 36, 4);
        if (wanted(sp, spr)) return true;
    }
    return false;
}

std::vector<RelayEvent> SparkplugRun::all_events() const {
    std::vector<RelayEvent> all;
    for (const auto& relay : relays_) {
        for (auto& e : relay->events()) all.push_back(std::move(e));
    }
    return all;
}

std::size_t SparkplugRun::count_sent(std::size_t b, const std::string& type) const {
    NodeView probe;
    std::size_t count = 0;
    for (std::size_t r = 0; r < relays_.size(); ++r) {
        if (b <= 1 && r != b) continue;
        for (const auto& e : relays_[r]->events()) {
            if (e.from_client() && !e.closed() && e.packet->type == PacketType::publish &&
                probe.type_of(e.packet->topic) == type) {
                ++count;
            }
        }
    }
    return count;
}

bool SparkplugRun::sent(const std::string& type, std::size_t count, std::size_t b) {
    // Bounded polling: the relays record on their own threads, each with its own wait.
    const auto deadline = std::chrono::steady_clock::now() + 30s;
    while (count_sent(b, type) < count) {
        if (std::chrono::steady_clock::now() > deadline) return false;
        std::this_thread::sleep_for(20ms);
    }
    return true;
}

bool SparkplugRun::subscribed_to_state(std::size_t b, std::size_t count) {
    return relays_.at(b)->wait_for(
        [count](const MqttRelay::Events& events) {
            std::size_t acknowledged = 0;
            bool asked = false;
            for (const auto& e : events) {
                if (e.closed()) continue;
                if (e.from_client() && e.packet->type == PacketType::subscribe) {
                    for (const auto& f : e.packet->filters) asked |= f == "spBv1.0/STATE/scada";
                }
                if (!e.from_client() && e.packet->type == PacketType::suback && asked) {
                    ++acknowledged;
                    asked = false;
                }
            }
            return acknowledged >= count;
        },
        30s);
}

void SparkplugRun::mark(const std::string& what) {
    marks_[what] = std::chrono::steady_clock::now();
}

NodeView SparkplugRun::view() const {
    auto view = node_view(all_events());
    view.marks = marks_;
    view.wall_from_ms = wall_from_ms_;
    view.wall_to_ms = wall_ms();
    return view;
}

std::vector<std::string> SparkplugRun::payloads() const {
    std::vector<std::string> out;
    for (const auto& c : view().connections) {
        for (const auto& p : c.packets) {
            if (p.from_node && p.payload) out.push_back(p.packet.payload);
        }
        if (c.connect.will) out.push_back(c.connect.will->payload);
    }
    return out;
}

}  // namespace eip2mqtt::test::conformance
