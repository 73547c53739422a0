// A hot-standby pair goes on where its leader stopped (docs/redundancy.md): two real gateways
// on one real Mosquitto, both with the same produced exchange sent to the test's socket. The
// standby follows the images the leader publishes on the pair's topics, so the first datagram
// of a new leader carries the last value written to the killed one. And where both units hear
// the produced datagrams (the test forwards each one it captures to both units' ports, as a
// multicast group both join would), the new leader's request ids go on from the last one the
// killed leader sent, so consumers see one producer, not a restart.

#include <signal.h>

#include <functional>
#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"
#include "tests/support/pair_fixture.hpp"
#include "tests/support/schema_check.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using json = nlohmann::json;

const std::string image_topic = "test/_gateway/_pair/turbine/image/sp";

/// SPEED_SP (a real at byte 0) in a datagram's data.
double speed_sp(std::span<const std::byte> data) {
    return std::get<float>(core::plan::decode_value(data, core::plan::TagType::real, {0, 0}));
}

class HotStandbyContinuityTest : public PairTest {
protected:
    void SetUp() override {
        broker_ = std::make_unique<Mosquitto>();
        recorder_ = std::make_unique<MqttRecorder>(broker_->url(), std::vector<std::string>{"#"});
        start_units([&](const std::string& id, std::uint16_t port) {
            return pair_config(id, broker_->url(), port, 50);
        });
    }

    /// The next metrics of `id` whose `pair` object satisfies `pred`, checked against the schema,
    /// whole.
    std::optional<json> pair_metrics(const std::string& id,
                                     const std::function<bool(const json&)>& pred) {
        const auto message = recorder_->wait_for_message(
            "test/_gateway/" + id + "/metrics",
            [&](const std::string& p) {
                const auto j = json::parse(p, nullptr, false);
                return j.is_object() && j.contains("pair") && pred(j["pair"]);
            },
            10s);
        if (!message) return std::nullopt;
        EXPECT_EQ(schema_problem(schema_file("metrics.json"), message->payload), "");
        return json::parse(message->payload);
    }
    /// The next produced datagram, forwarded to the units still running when `forward`.
    std::optional<UdpDatagram> next(bool forward) {
        auto datagram = capture_.receive_from(10s);
        if (datagram && forward) forward_to_units(*datagram);
        return datagram;
    }
    void forward_to_units(const UdpDatagram& datagram) {
        for (const auto& [id, gateway] : gateways_) {
            if (gateway) capture_.send_to(ports_.at(id), datagram.bytes);
        }
    }
    void kill(const std::string& id) {
        gateways_[id]->signal(SIGKILL);
        ASSERT_TRUE(gateways_[id]->wait(10s).has_value());
        gateways_[id].reset();
    }

    /// What a write around a leader's death came to: the new leader's first datagram's value,
    /// and every answer the write got.
    struct AfterDeath {
        double produced = 0;
        std::vector<json> answers;
    };
    /// Writes 3100 to the leader, waits for its answer when `answered_first`, kills it, then
    /// reads the new leader's first datagram. The answers are counted once the new leader
    /// answered a later write (on a response topic of its own): it answers in order, after
    /// whatever it settled as it took the lead.
    std::optional<AfterDeath> write_then_kill(bool answered_first) {
        const auto old = leader_beside_standby();
        const auto first = next(false);
        if (old.empty() || !first) return fail("nobody leads and produces");
        recorder_->publish(set_topic, "3100");
        if (answered_first && !recorder_->wait_for_message(result_topic, nullptr, 10s)) {
            return fail("the leader never answered the write");
        }
        const auto killed = recorder_->count();
        kill(old);
        if (HasFatalFailure() || !says(other(old), "leader", killed)) return fail("no takeover");
        std::optional<UdpDatagram> taken_over;
        for (int i = 0; i < 400 && !taken_over; ++i) {
            auto datagram = next(false);
            if (!datagram) break;
            if (datagram->from_port != first->from_port) taken_over = std::move(datagram);
        }
        if (!taken_over) return fail("the new leader produced nothing");
        const auto decoded = core::wire::decode_datagram(taken_over->bytes);
        if (!decoded.ok()) return fail("the new leader's datagram does not decode");
        recorder_->publish_request(set_topic, "3000", "client/barrier", "barrier");
        if (!recorder_->wait_for_message("client/barrier", nullptr, 10s)) {
            return fail("the new leader never answered a write");
        }
        AfterDeath out{speed_sp(decoded->data), {}};
        for (const auto& answer : recorder_->messages_on(result_topic)) {
            out.answers.push_back(json::parse(answer.payload));
        }
        return out;
    }
    static std::optional<AfterDeath> fail(const std::string& why) {
        ADD_FAILURE() << why;
        return std::nullopt;
    }

    const std::string set_topic = "test/sp/SPEED_SP/set";
    const std::string result_topic = set_topic + "/result";
};

TEST_F(HotStandbyContinuityTest, TheNewLeadersFirstDatagramCarriesTheValueWrittenToTheKilledOne) {
    const auto old = leader_beside_standby();
    ASSERT_FALSE(old.empty()) << "nobody leads";
    const auto standby = other(old);
    const auto first = next(false);
    ASSERT_TRUE(first.has_value());

    const auto from = recorder_->count();
    recorder_->publish("test/sp/SPEED_SP/set", "3100");
    const auto result = recorder_->wait_for_message("test/sp/SPEED_SP/set/result", nullptr, 10s);
    ASSERT_TRUE(result.has_value());
    ASSERT_EQ(json::parse(result->payload), json({{"ok", true}}));
    // The leader's image, retained for the standby, carries the write.
    // 3100.0 as a little-endian IEEE-754 single: 0x4541C000.
    const auto image = recorder_->wait_for_message(
        image_topic,
        [](const std::string& p) {
            const auto j = json::parse(p, nullptr, false);
            return j.is_object() && j.value("data", "") == "00c04145";
        },
        10s, from);
    ASSERT_TRUE(image.has_value());
    EXPECT_EQ(json::parse(image->payload).value("id", ""), old);
    EXPECT_EQ(schema_problem(schema_file("pair-image.json"), image->payload), "");

    const auto killed = recorder_->count();
    kill(old);
    ASSERT_TRUE(says(standby, "leader", killed));
    // Every datagram left in the capture from the killed leader, then the new leader's first.
    std::optional<UdpDatagram> taken_over;
    for (int i = 0; i < 400 && !taken_over; ++i) {
        auto datagram = next(false);
        ASSERT_TRUE(datagram.has_value()) << "the new leader produced nothing";
        if (datagram->from_port != first->from_port) taken_over = std::move(datagram);
    }
    ASSERT_TRUE(taken_over.has_value());
    const auto decoded = core::wire::decode_datagram(taken_over->bytes);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(speed_sp(decoded->data), 3100.0);
    // The image it took is counted, none ignored.
    const auto metrics = pair_metrics(standby, [](const json& p) {
        return p.value("images_followed", 0) >= 1 && p.value("images_published", 0) >= 1;
    });
    ASSERT_TRUE(metrics.has_value());
    EXPECT_EQ(
        metrics->at("pair").at("images_ignored"),
        json({{"other_layout", 0}, {"stale", 0}, {"unknown_exchange", 0}, {"not_an_image", 0}}));
}

TEST_F(HotStandbyContinuityTest, RequestIdsGoOnFromTheKilledLeadersLastWhenBothHearThem) {
    const auto old = leader_beside_standby();
    ASSERT_FALSE(old.empty()) << "nobody leads";
    const auto standby = other(old);
    std::optional<UdpDatagram> last;
    for (int i = 0; i < 20; ++i) {
        last = next(true);
        ASSERT_TRUE(last.has_value());
    }
    const auto old_port = last->from_port;

    const auto killed = recorder_->count();
    kill(old);
    // All the killed leader sent is in the capture by now (loopback delivers within the send):
    // forwarded at once, long before the standby may take over.
    while (auto datagram = capture_.receive_from(0ms)) {
        ASSERT_EQ(datagram->from_port, old_port);
        forward_to_units(*datagram);
        last = std::move(datagram);
    }
    ASSERT_TRUE(says(standby, "leader", killed));
    std::optional<UdpDatagram> taken_over;
    for (int i = 0; i < 400 && !taken_over; ++i) {
        auto datagram = next(true);
        ASSERT_TRUE(datagram.has_value()) << "the new leader produced nothing";
        if (datagram->from_port == old_port) {
            last = std::move(datagram);
        } else {
            taken_over = std::move(datagram);
        }
    }
    ASSERT_TRUE(taken_over.has_value());
    const auto old_header = core::wire::decode_datagram(last->bytes);
    const auto new_header = core::wire::decode_datagram(taken_over->bytes);
    ASSERT_TRUE(old_header.ok());
    ASSERT_TRUE(new_header.ok());
    EXPECT_EQ(new_header->header.request_id,
              static_cast<std::uint16_t>(old_header->header.request_id + 1));
    // The standby heard every datagram forwarded to it, none of them counted as dropped.
    const auto metrics =
        pair_metrics(standby, [](const json& p) { return p.value("produced_heard", 0) >= 20; });
    ASSERT_TRUE(metrics.has_value());
    EXPECT_EQ(metrics->at("dropped").value("unknown_exchange", -1), 0);
}

TEST_F(HotStandbyContinuityTest, AWriteTheLeaderAnsweredJustBeforeItDiedIsAnsweredOnceAndKept) {
    const auto after = write_then_kill(true);
    ASSERT_TRUE(after.has_value());
    ASSERT_EQ(after->answers.size(), 1u) << ::testing::PrintToString(after->answers);
    EXPECT_EQ(after->answers[0], json({{"ok", true}}));
    EXPECT_EQ(after->produced, 3100.0) << "answered ok, then undone by the new leader";
}

TEST_F(HotStandbyContinuityTest, AWriteInFlightWhenTheLeaderDiesIsAnsweredOnceAndOkOnlyIfKept) {
    // Whatever the killed leader did with it (nothing, produced it, answered it), one answer,
    // and it says what the new leader produces.
    const auto after = write_then_kill(false);
    ASSERT_TRUE(after.has_value());
    ASSERT_EQ(after->answers.size(), 1u) << ::testing::PrintToString(after->answers);
    if (after->answers[0].value("ok", false)) {
        EXPECT_EQ(after->produced, 3100.0) << "answered ok, then undone by the new leader";
    } else {
        EXPECT_EQ(after->answers[0], json({{"ok", false}, {"error", "standby"}}));
        EXPECT_EQ(after->produced, 3000.0) << "refused, yet produced by the new leader";
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
