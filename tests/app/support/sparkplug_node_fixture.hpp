#pragma once
// The Sparkplug edge node over a recording publisher, for its unit tests: two devices ("in",
// consumed; "out", produced), payloads read back with the protobuf classes of our .proto, and
// the node's tick driven by the test's own clock.

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "sparkplug_b.pb.h"
#include "tests/app/support/json_tree_recorder.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/fake_clock.hpp"

namespace eip2mqtt::test {

using SparkplugProto = org::eclipse::tahu::protobuf::Payload;

inline constexpr std::int64_t now_ms = 1700000000000;

/// A (dint, with a unit and a max), B (real) and C (dint, read-only).
inline core::plan::ExchangePlan sparkplug_plan(std::string name, core::plan::Direction direction) {
    using core::plan::TagType;
    auto a = test_tag("A", 0, TagType::dint, true);
    a.mutable_extras().unit = "rpm";
    a.mutable_extras().max = 4000;
    return test_plan(name, direction, 12,
                     {a, test_tag("B", 4, TagType::real, true), test_tag("C", 8, TagType::dint)});
}

inline SparkplugProto decoded(const adapters::mqtt::Message& message) {
    SparkplugProto proto;
    EXPECT_TRUE(proto.ParseFromString(message.payload)) << message.topic;
    return proto;
}

inline std::string command(std::vector<adapters::sparkplug::Metric> metrics) {
    adapters::sparkplug::Payload payload;
    payload.timestamp_ms = now_ms;
    payload.metrics = std::move(metrics);
    return adapters::sparkplug::encode(payload);
}

/// `command(metrics)` with no datatype on any metric: the form Sparkplug B 3.0 recommends for
/// NCMD and DCMD (a host that uses aliases sends alias and value alone).
inline std::string untyped_command(std::vector<adapters::sparkplug::Metric> metrics) {
    SparkplugProto proto;
    EXPECT_TRUE(proto.ParseFromString(command(std::move(metrics))));
    for (auto& metric : *proto.mutable_metrics()) metric.clear_datatype();
    return proto.SerializeAsString();
}

inline adapters::sparkplug::Metric by_name(std::string name, adapters::sparkplug::DataType type,
                                           core::plan::Value value) {
    return {std::move(name), std::nullopt, now_ms, type, value, false, {}};
}

class SparkplugNodeTest : public ::testing::Test, public app::WriteHandler {
protected:
    using Value = core::plan::Value;
    using Quality = core::quality::Quality;

    explicit SparkplugNodeTest(std::string primary_host = "", std::size_t max_packet_bytes = 0,
                               std::optional<std::uint8_t> last_bd_seq = std::nullopt)
        : node_({"plant1", "gw1", std::move(primary_host), max_packet_bytes, last_bd_seq},
                publisher_, *this, wall_clock_, [this] { ++brokers_left_; }) {
        node_.exchanges_changed({{&consumed_}, {&produced_}}, {});
        node_.tick(clock_);
    }

    void on_write(app::WriteRequest&& request) override { writes_.push_back(std::move(request)); }

    /// The gateway's tick, `by` after the last.
    void advance(std::chrono::milliseconds by) {
        clock_ += by;
        node_.tick(clock_);
    }
    void connect() {
        node_.next_will();
        node_.on_connected();
    }
    std::vector<std::string> topics() const {
        std::vector<std::string> out;
        for (const auto& m : publisher_.published) out.push_back(m.topic);
        return out;
    }
    std::size_t count_of(const std::string& topic) const { return publisher_.on(topic).size(); }
    std::vector<std::uint64_t> seqs() const {
        std::vector<std::uint64_t> out;
        for (const auto& m : publisher_.published) out.push_back(decoded(m).seq());
        return out;
    }
    /// The consumed exchange's first datagram, as the ExchangeConsumer reports it.
    void first_datagram() {
        const std::vector<app::TagSample> samples{
            {0, Value{std::int64_t{7}}}, {1, Value{1.5f}}, {2, Value{std::int64_t{0}}}};
        node_.tag_samples({consumed_, Quality::good, now_ms - 5, false, samples});
        node_.exchange_state(consumed_, core::exchange::ConsumeState::ok);
    }
    /// The produced exchange's first datagram sent: every value echoed.
    void first_production() {
        const std::vector<app::TagSample> samples{
            {0, Value{std::int64_t{0}}}, {1, Value{0.0f}}, {2, Value{std::int64_t{0}}}};
        node_.tag_samples({produced_, Quality::good, now_ms - 2, false, samples});
    }
    adapters::mqtt::Incoming dcmd(std::string payload, std::string device = "out") {
        adapters::mqtt::Incoming in;
        in.topic = "spBv1.0/plant1/DCMD/gw1/" + device;
        in.payload = std::move(payload);
        return in;
    }
    void rebirth_request() {
        adapters::mqtt::Incoming ncmd;
        ncmd.topic = "spBv1.0/plant1/NCMD/gw1";
        ncmd.payload = command(
            {by_name("Node Control/Rebirth", adapters::sparkplug::DataType::boolean, Value{true})});
        node_.on_message(ncmd);
    }
    core::write::WriteError rejection(std::size_t i) const {
        return std::get<core::write::WriteRejection>(writes_.at(i).outcome).error;
    }

    core::plan::ExchangePlan consumed_ = sparkplug_plan("in", core::plan::Direction::consume);
    core::plan::ExchangePlan produced_ = sparkplug_plan("out", core::plan::Direction::produce);
    RecordingPublisher publisher_;
    std::vector<app::WriteRequest> writes_;
    /// Starts a day into the steady clock, as a gateway's does.
    core::MonoTime clock_ = core::MonoTime{} + std::chrono::hours(24);
    FakeClock wall_clock_{core::WallTime{std::chrono::milliseconds(now_ms)}};
    int brokers_left_ = 0;  ///< the node's leave_broker() calls
    app::northbound::sparkplug::SparkplugNode node_;
};

class SparkplugPrimaryHostTest : public SparkplugNodeTest {
protected:
    SparkplugPrimaryHostTest() : SparkplugNodeTest("scada") {}
    void state(std::string payload) {
        adapters::mqtt::Incoming in;
        in.topic = "spBv1.0/STATE/scada";
        in.payload = std::move(payload);
        in.retained = true;
        node_.on_message(in);
    }
    void state(bool online, std::int64_t timestamp) {
        state(std::string(R"({"online":)") + (online ? "true" : "false") + R"(,"timestamp":)" +
              std::to_string(timestamp) + "}");
    }
};

}  // namespace eip2mqtt::test
