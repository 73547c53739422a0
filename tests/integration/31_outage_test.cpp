// Broker outages: a broker restart under traffic (buffering, order, retained state, writes),
// and writes that wait in the broker's persistent session while the gateway is down.

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

constexpr std::int64_t constant = -4242;

std::string exchanges(std::uint16_t capture_port) {
    return ExchangeYaml::consume("line", "10.0.0.2", 7)
               .length(8)
               .period_ms(20)
               .timeout_ms(0)
               .tag("MARKER", "0.0", "udint")
               .tag("CONSTANT", "4.0", "dint")
               .str() +
           ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture_port))
               .period_ms(20)
               .tag("SPEED_SP", "0.0", "real", "writable: true, min: 0, max: 4000, initial: 3000")
               .tag("LEVEL", "4.0", "int", "writable: true")
               .str();
}

std::vector<std::byte> marker_datagram(std::uint32_t marker) {
    return DatagramBuilder("10.0.0.2", 7, 8)
        .request_id(static_cast<std::uint16_t>(marker))
        .set("0.0", TagType::udint, std::uint64_t{marker})
        .set("4.0", TagType::dint, constant)
        .build();
}

Value tag(const std::vector<std::byte>& bytes, const char* address, TagType type) {
    return core::plan::decode_value(std::span(bytes).subspan(32), type,
                                    core::plan::parse_address(address).value());
}

/// A producer sending the `line` exchange every 20 ms, MARKER counting up from 1.
class Traffic {
public:
    explicit Traffic(std::function<void(const std::vector<std::byte>&)> send)
        : thread_([this, send = std::move(send)] {
              while (!stop_) {
                  send(marker_datagram(marker_ + 1));
                  ++marker_;
                  std::this_thread::sleep_for(20ms);  // pacing the traffic, not synchronising
              }
          }) {}
    ~Traffic() { stop(); }
    /// Stops sending; returns the last MARKER sent.
    std::uint32_t stop() {
        stop_ = true;
        if (thread_.joinable()) thread_.join();
        return marker_;
    }
    std::uint32_t last() const { return marker_; }

private:
    std::atomic<bool> stop_{false};
    std::atomic<std::uint32_t> marker_{0};
    std::thread thread_;
};

class OutageTest : public GatewayTest {
protected:
    void start_with(const std::string& mqtt_extra, GatewayOptions options = {}) {
        capture_ = std::make_unique<UdpClient>();
        start(exchanges(capture_->port()), mqtt_extra, std::move(options));
        ASSERT_TRUE(capture_->receive(5s).has_value()) << "the gateway is not producing";
    }

    /// The MARKER values recorded after index `from`, in arrival order.
    std::vector<std::uint64_t> markers(std::size_t from) const {
        std::vector<std::uint64_t> values;
        const auto all = recorder_->messages();
        for (std::size_t i = from; i < all.size(); ++i) {
            if (all[i].topic != topic("line/MARKER")) continue;
            values.push_back(json::parse(all[i].payload)["value"].get<std::uint64_t>());
        }
        return values;
    }

    /// Waits for a produced datagram whose SPEED_SP is `expected`.
    bool produces_speed(float expected) {
        const auto deadline = std::chrono::steady_clock::now() + 5s;
        while (std::chrono::steady_clock::now() < deadline) {
            const auto bytes = capture_->receive(1s);
            if (bytes && tag(*bytes, "0.0", TagType::real) == Value{expected}) return true;
        }
        return false;
    }

    /// The latest produced datagram.
    std::vector<std::byte> latest() {
        return capture_->latest(5s).value_or(std::vector<std::byte>(64));
    }

    /// Publishes a write until it is answered, and returns the answer. Right after a connect
    /// the gateway's SUBSCRIBE may still be on its way, and a write published before it is
    /// not for the gateway: each attempt waits a bounded time for the result.
    std::optional<json> write_until_answered(const std::string& topic_suffix,
                                             const std::string& payload) {
        for (int attempt = 0; attempt < 10; ++attempt) {
            const auto from = recorder_->count();
            recorder_->publish(topic(topic_suffix), payload);
            if (const auto result = recorder_->wait_for_message(topic(topic_suffix + "/result"),
                                                                nullptr, 1s, from)) {
                return json::parse(result->payload);
            }
        }
        ADD_FAILURE() << "no result for " << topic_suffix << " " << payload;
        return std::nullopt;
    }

    /// Kills the gateway (no clean stop: the broker keeps its session) and waits for the will.
    void kill_gateway() {
        // Its subscriptions are in place once a write is answered: only then does the broker
        // keep writes for it.
        ASSERT_TRUE(write_until_answered("sp/LEVEL/set", "1").has_value());
        const auto from = recorder_->count();
        gateway_->signal(SIGKILL);
        ASSERT_TRUE(gateway_->wait(5s).has_value());
        ASSERT_TRUE(recorder_->wait_for_message(
            availability_topic(), [](const std::string& p) { return p == "offline"; }, 10s, from));
    }

    std::unique_ptr<UdpClient> capture_;
};

TEST_F(OutageTest, BrokerRestartUnderTrafficLosesNothingThatMatters) {
    GatewayOptions options;
    options.broker.persistence = true;
    start_with("", options);
    Traffic traffic([this](const std::vector<std::byte>& d) { send(d); });

    // Values flow.
    ASSERT_TRUE(recorder_->wait_for_message(topic("line/MARKER"), nullptr, 10s));
    expect_field(topic("line/CONSTANT"), "value", std::to_string(constant));
    const auto constants_before = recorder_->messages_on(topic("line/CONSTANT")).size();

    // The outage: several seconds without a broker, traffic going on.
    broker_->stop();
    ASSERT_TRUE(gateway_->wait_for_output("MQTT connection to", 10s)) << gateway_->output();
    const auto marker_at_stop = traffic.last();
    std::this_thread::sleep_for(3s);  // the scenario: the broker stays down
    const auto from = recorder_->count();
    broker_->start();

    // The gateway comes back by itself (its backoff grew meanwhile), and live values follow.
    wait_online(from);
    const auto at_online = traffic.last();
    ASSERT_TRUE(recorder_->wait_for_message(
        topic("line/MARKER"),
        [&](const std::string& p) { return json::parse(p)["value"] > at_online; }, 10s, from));
    const auto last = traffic.stop();

    // The last value arrives, and what the gateway published after the outage began, first
    // from its buffer then live, arrives in order. (Values from before the outage may come
    // again: QoS 1 publications unconfirmed when the connection dropped are sent again.)
    ASSERT_TRUE(recorder_->wait_for_message(
        topic("line/MARKER"), [&](const std::string& p) { return json::parse(p)["value"] == last; },
        15s, from))
        << "the last MARKER never arrived";
    std::vector<std::uint64_t> after_outage;
    for (const auto v : markers(from)) {
        if (v > marker_at_stop) after_outage.push_back(v);
    }
    EXPECT_GE(after_outage.size(), 2u);
    EXPECT_TRUE(std::adjacent_find(after_outage.begin(), after_outage.end(),
                                   std::greater_equal<>()) == after_outage.end())
        << "MARKER values after the outage are not increasing";
    EXPECT_EQ(after_outage.back(), last);

    // Retained state is republished: CONSTANT never changed, yet it is published again.
    ASSERT_TRUE(recorder_->wait_for(
        [&](const std::vector<Received>& all) {
            return std::count_if(all.begin(), all.end(), [&](const Received& m) {
                       return m.topic == topic("line/CONSTANT");
                   }) > static_cast<std::ptrdiff_t>(constants_before);
        },
        10s))
        << "CONSTANT was not republished after the reconnect";
    expect_field(topic("line/_status"), "state", "\"ok\"", from);

    // Writes are accepted again.
    EXPECT_EQ(write_until_answered("sp/SPEED_SP/set", "1234.5"), json({{"ok", true}}));
    EXPECT_TRUE(produces_speed(1234.5f));
}

TEST_F(OutageTest, WriteSentWhileTheGatewayWasDownIsAppliedFromItsSession) {
    start_with("  session_expiry_s: 300\n");
    kill_gateway();

    const auto from = recorder_->count();
    recorder_->publish(topic("sp/SPEED_SP/set"), "2100");
    start_gateway();

    const auto result =
        recorder_->wait_for_message(topic("sp/SPEED_SP/set/result"), nullptr, 10s, from);
    ASSERT_TRUE(result.has_value()) << "the queued write was not applied; output:\n"
                                    << gateway_->output();
    EXPECT_EQ(json::parse(result->payload), json({{"ok", true}}));
    EXPECT_TRUE(produces_speed(2100.0f));
}

TEST_F(OutageTest, ExpiredWriteIsDroppedByTheBroker) {
    start_with("  session_expiry_s: 300\n");
    kill_gateway();

    const auto from = recorder_->count();
    recorder_->publish_with_expiry(topic("sp/SPEED_SP/set"), "2100", 1s);
    std::this_thread::sleep_for(3s);  // the scenario: the gateway stays down past the expiry
    start_gateway();

    // A later write is delivered after anything the session still held, so once its result is
    // in, the expired one would have been answered too.
    const auto later_from = recorder_->count();
    recorder_->publish(topic("sp/LEVEL/set"), "17");
    const auto later =
        recorder_->wait_for_message(topic("sp/LEVEL/set/result"), nullptr, 10s, later_from);
    ASSERT_TRUE(later.has_value()) << gateway_->output();
    EXPECT_EQ(json::parse(later->payload), json({{"ok", true}}));

    EXPECT_FALSE(recorder_->wait_for_message(topic("sp/SPEED_SP/set/result"), nullptr, 0ms, from))
        << "the expired write was answered";
    const auto bytes = latest();
    EXPECT_EQ(tag(bytes, "0.0", TagType::real), Value{3000.0f});
    EXPECT_EQ(tag(bytes, "4.0", TagType::int_), Value{std::int64_t{17}});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
