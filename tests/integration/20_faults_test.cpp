// Network faults are detected, counted and never turn into wrong values: datagrams go from the
// test through the real fault injector (a child process) to the real gateway, and the injector's
// report says exactly which faults it injected, so that `_status` and the metrics can be checked
// against it. MARKER carries each datagram's request id: a duplicate or late datagram that was
// consumed would publish an old value, so the values on its topic must strictly increase.

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;

constexpr auto injector_timeout = std::chrono::seconds(30);

std::string exchange_yaml(int timeout_ms) {
    return ExchangeYaml::consume("unit1", "10.0.0.1", 1)
        .length(8)
        .period_ms(100)
        .timeout_ms(timeout_ms)
        .tag("MARKER", "0.0", "word")
        .tag("VALUE", "4.0", "dint")
        .str();
}

std::vector<std::byte> datagram(std::uint16_t rid, std::int64_t value = 1000) {
    return DatagramBuilder("10.0.0.1", 1, 8)
        .request_id(rid)
        .set("0.0", TagType::word, std::uint64_t{rid})
        .set("4.0", TagType::dint, value)
        .build();
}

class FaultsTest : public GatewayTest {
protected:
    /// Starts the injector between the test and the gateway, with the given fault options;
    /// it stops after `count` datagrams.
    void start_injector(std::vector<std::string> faults, std::uint64_t count) {
        injector_port_ = free_udp_port();
        report_path_ = dir_.path() + "/report-" + std::to_string(++runs_) + ".json";
        std::vector<std::string> argv = {EIP2MQTT_FAULT_INJECTOR,
                                         "--listen",
                                         "127.0.0.1:" + std::to_string(injector_port_),
                                         "--to",
                                         "127.0.0.1:" + std::to_string(udp_port_),
                                         "--count",
                                         std::to_string(count),
                                         "--duration",
                                         "60",
                                         "--report-json",
                                         report_path_};
        argv.insert(argv.end(), faults.begin(), faults.end());
        injector_ = std::make_unique<ChildProcess>(std::move(argv));
        ASSERT_TRUE(injector_->wait_for_output("listening on")) << injector_->output();
    }

    void send_via_injector(const std::vector<std::byte>& bytes) {
        udp_->send_to(injector_port_, bytes);
    }

    /// Waits for the injector to stop (it has forwarded everything due) and returns its report.
    json finish_injector() {
        const auto status = injector_->wait(injector_timeout);
        EXPECT_EQ(status, 0) << injector_->output();
        std::ifstream file(report_path_);
        const auto report = json::parse(file, nullptr, false);
        EXPECT_TRUE(report.is_object()) << injector_->output();
        return report;
    }

    /// The next `_status` of unit1 that satisfies `pred`; fails the test on timeout.
    json wait_status(const std::function<bool(const json&)>& pred, std::size_t from = 0) {
        const auto m = recorder_->wait_for_message(
            topic("unit1/_status"), [&](const std::string& p) { return pred(json::parse(p)); },
            std::chrono::seconds(10), from);
        if (!m) {
            const auto last = recorder_->last(topic("unit1/_status"));
            ADD_FAILURE() << "no matching _status; last: " << (last ? last->payload : "none");
            return json::object();
        }
        return json::parse(m->payload);
    }

    /// The next metrics message that satisfies `pred`; fails the test on timeout.
    json wait_metrics(const std::function<bool(const json&)>& pred) {
        const auto m = recorder_->wait_for_message(
            metrics_topic(), [&](const std::string& p) { return pred(json::parse(p)); },
            std::chrono::seconds(10));
        if (!m) {
            const auto last = recorder_->last(metrics_topic());
            ADD_FAILURE() << "no matching metrics; last: " << (last ? last->payload : "none");
            return json::object();
        }
        return json::parse(m->payload);
    }

    std::vector<std::int64_t> values_of(const std::string& tag) const {
        std::vector<std::int64_t> values;
        for (const auto& m : recorder_->messages_on(topic("unit1/" + tag))) {
            values.push_back(json::parse(m.payload)["value"].get<std::int64_t>());
        }
        return values;
    }

    void expect_strictly_increasing_markers() const {
        const auto markers = values_of("MARKER");
        for (std::size_t i = 1; i < markers.size(); ++i) {
            EXPECT_LT(markers[i - 1], markers[i]) << "MARKER republished an old value at " << i;
        }
    }

    /// Sends rid 0 straight to the gateway and waits until it is consumed, so that the
    /// sequence is synchronised before any fault.
    void prime() {
        send(datagram(0));
        expect_field(topic("unit1/MARKER"), "value", "0");
    }

    /// Sends rids 1..n through the injector, then rid n + 1 straight to the gateway once the
    /// injector has forwarded everything, so that the last gap is closed by a clean sample.
    json run_sequence(std::vector<std::string> faults, std::uint16_t n) {
        start_injector(std::move(faults), n);
        for (std::uint16_t rid = 1; rid <= n; ++rid) send_via_injector(datagram(rid));
        auto report = finish_injector();
        send(datagram(static_cast<std::uint16_t>(n + 1)));
        expect_field(topic("unit1/MARKER"), "value", std::to_string(n + 1));
        return report;
    }

    static std::uint64_t affected(const json& report, const char* fault) {
        return report["faults"][fault]["affected"].get<std::uint64_t>();
    }

    std::unique_ptr<ChildProcess> injector_;
    std::uint16_t injector_port_ = 0;
    std::string report_path_;
    int runs_ = 0;
};

TEST_F(FaultsTest, LossAndBurstGapsAreCountedAsMissed) {
    start(exchange_yaml(0));
    prime();
    const auto report = run_sequence({"--seed", "7", "--loss", "0.2", "--loss-burst", "2"}, 200);
    const auto lost = affected(report, "loss");
    ASSERT_GT(lost, 0u);
    ASSERT_EQ(report["out"], 200 - lost);
    const auto received = 2 + report["out"].get<std::uint64_t>();
    const auto status = wait_status([&](const json& s) { return s["received"] == received; });
    EXPECT_EQ(status["missed"], lost);
    EXPECT_EQ(status["accepted"], received);
    EXPECT_EQ(status["duplicates"], 0);
    EXPECT_EQ(status["out_of_order"], 0);
    EXPECT_EQ(status["request_id"], 201);
    expect_strictly_increasing_markers();
}

TEST_F(FaultsTest, DuplicatesAreCountedAndNeverPublishedAsNewValues) {
    start(exchange_yaml(0));
    prime();
    const auto report = run_sequence({"--seed", "11", "--duplicate", "0.3"}, 200);
    const auto duplicated = affected(report, "duplicate");
    ASSERT_GT(duplicated, 0u);
    const auto received = 2 + report["out"].get<std::uint64_t>();
    const auto status = wait_status([&](const json& s) { return s["received"] == received; });
    EXPECT_EQ(status["duplicates"], duplicated);
    EXPECT_EQ(status["accepted"], 202);
    EXPECT_EQ(status["missed"], 0);
    EXPECT_EQ(status["out_of_order"], 0);
    expect_strictly_increasing_markers();
}

TEST_F(FaultsTest, ReorderedDatagramsAreCountedAndNeverPublishedAsNewValues) {
    start(exchange_yaml(0));
    prime();
    const auto report = run_sequence({"--seed", "5", "--reorder", "0.2"}, 200);
    const auto reordered = affected(report, "reorder");
    ASSERT_GT(reordered, 0u);
    const auto received = 2 + report["out"].get<std::uint64_t>();
    const auto status = wait_status([&](const json& s) { return s["received"] == received; });
    // Each late datagram is dropped as out of order, and its request id was missed when the
    // next one was accepted ahead of it.
    EXPECT_EQ(status["out_of_order"], reordered);
    EXPECT_EQ(status["missed"], reordered);
    EXPECT_EQ(status["accepted"], received - reordered);
    EXPECT_EQ(status["duplicates"], 0);
    expect_strictly_increasing_markers();
}

TEST_F(FaultsTest, MixedLossDuplicationAndReorderingAddUp) {
    start(exchange_yaml(0));
    prime();
    const auto report = run_sequence({"--seed", "23", "--loss", "0.1", "--duplicate", "0.1",
                                      "--reorder", "0.1", "--jitter", "0.1:2"},
                                     500);
    const auto received = 2 + report["out"].get<std::uint64_t>();
    const auto status = wait_status([&](const json& s) { return s["received"] == received; });
    EXPECT_EQ(status["accepted"].get<std::uint64_t>() + status["duplicates"].get<std::uint64_t>() +
                  status["out_of_order"].get<std::uint64_t>(),
              received);
    EXPECT_GE(status["duplicates"].get<std::uint64_t>(), 1u);
    EXPECT_GE(status["out_of_order"].get<std::uint64_t>(), 1u);
    // Every request id 0..501 was either accepted or counted as missed.
    EXPECT_EQ(status["accepted"].get<std::uint64_t>() + status["missed"].get<std::uint64_t>(),
              502u);
    expect_strictly_increasing_markers();
    const auto metrics = wait_metrics([&](const json& m) { return m["datagrams"] == received; });
    EXPECT_EQ(metrics["dropped"]["duplicate"], status["duplicates"]);
    EXPECT_EQ(metrics["dropped"]["out_of_order"], status["out_of_order"]);
}

TEST_F(FaultsTest, LateDataAfterTheTimeoutIsMarkedStaleThenRecovers) {
    start(exchange_yaml(300));
    prime();
    const auto from = recorder_->count();
    start_injector({"--delay", "1500"}, 1);
    send_via_injector(datagram(1));
    // The datagram is held 1.5 s, longer than timeout_ms: the exchange goes stale first...
    const auto stale = recorder_->wait_for_message(
        topic("unit1/MARKER"),
        [](const std::string& p) { return json::parse(p)["quality"] == "stale"; },
        std::chrono::seconds(10), from);
    ASSERT_TRUE(stale.has_value());
    EXPECT_EQ(json::parse(stale->payload)["value"], 0);
    wait_status([](const json& s) { return s["state"] == "stale" && s["timeouts"] == 1; }, from);
    // ...then the late datagram arrives and recovers it with its value.
    const auto good = recorder_->wait_for_message(
        topic("unit1/MARKER"),
        [](const std::string& p) {
            const auto j = json::parse(p);
            return j["quality"] == "good" && j["value"] == 1;
        },
        std::chrono::seconds(10), from);
    ASSERT_TRUE(good.has_value());
    EXPECT_GT(good->at, stale->at);
    // (The `_status` of the first sample may arrive after `from`: wait for the recovered one.)
    const auto status =
        wait_status([](const json& s) { return s["state"] == "ok" && s["timeouts"] == 1; }, from);
    EXPECT_EQ(status["accepted"], 2);
    finish_injector();
}

TEST_F(FaultsTest, CorruptedHeadersAreDroppedAndCountedByReason) {
    start(exchange_yaml(0));
    prime();
    std::uint16_t rid = 1;
    const auto run = [&](const char* field) {
        start_injector({"--corrupt-field", std::string("1:") + field}, 10);
        for (int i = 0; i < 10; ++i, ++rid) send_via_injector(datagram(rid, 1000 + rid));
        const auto report = finish_injector();
        EXPECT_EQ(affected(report, "corrupt_field"), 10u) << field;
    };
    run("type");
    run("version");
    run("exchange");
    run("producer");
    // Status and reserved are recorded or ignored, never a reason to drop (§2, §4).
    run("status");
    run("reserved");
    const auto metrics = wait_metrics([](const json& m) { return m["datagrams"] == 61; });
    EXPECT_EQ(metrics["dropped"]["not_data_pdu"], 20);
    EXPECT_EQ(metrics["dropped"]["unknown_exchange"], 20);
    EXPECT_EQ(metrics["accepted"], 21);
    // Only the datagrams whose header survived were published.
    const auto markers = values_of("MARKER");
    for (const auto m : markers) EXPECT_TRUE(m == 0 || m > 40) << m;
    EXPECT_EQ(markers.back(), 60);
}

TEST_F(FaultsTest, CorruptedDataOfTheRightLengthIsPublished) {
    start(exchange_yaml(0));
    prime();
    // Bit 0 of data byte 4 (datagram bit 36 * 8): VALUE 1000 arrives as 1001. EIP has no
    // checksum, so the gateway cannot tell, and must publish what it received.
    start_injector({"--corrupt-bit", "1:288"}, 1);
    send_via_injector(datagram(1, 1000));
    finish_injector();
    const auto flipped = expect_field(topic("unit1/VALUE"), "value", "1001");
    EXPECT_EQ(json::parse(flipped.payload)["quality"], "good");

    start_injector({"--seed", "3", "--corrupt-byte", "1:36"}, 1);
    send_via_injector(datagram(2, 1000));
    finish_injector();
    expect_field(topic("unit1/MARKER"), "value", "2");
    const auto value = values_of("VALUE").back();
    EXPECT_NE(value, 1000);
    EXPECT_EQ(value & ~0xFF, 1000 & ~0xFF);  // only the low byte changed
    const auto status = wait_status([](const json& s) { return s["received"] == 3; });
    EXPECT_EQ(status["accepted"], 3);
}

TEST_F(FaultsTest, TruncatedDataIsRejectedAsLengthMismatch) {
    start(exchange_yaml(0));
    prime();
    start_injector({"--truncate", "1:38"}, 5);  // 6 of the 8 data bytes
    for (std::uint16_t rid = 1; rid <= 5; ++rid) send_via_injector(datagram(rid, 5000));
    finish_injector();
    const auto status = wait_status([](const json& s) { return s["received"] == 6; });
    EXPECT_EQ(status["state"], "length_mismatch");
    EXPECT_EQ(status["length_mismatches"], 5);
    EXPECT_EQ(status["accepted"], 1);
    expect_field(topic("unit1/VALUE"), "quality", "\"bad\"");
    for (const auto v : values_of("VALUE")) EXPECT_EQ(v, 1000);

    // At random lengths, each cut datagram is dropped for the reason its length gives.
    start_injector({"--seed", "9", "--truncate", "1"}, 50);
    for (std::uint16_t rid = 6; rid < 56; ++rid) send_via_injector(datagram(rid, 5000));
    const auto report = finish_injector();
    EXPECT_EQ(affected(report, "truncate"), 50u);
    const auto metrics = wait_metrics([](const json& m) { return m["datagrams"] == 56; });
    const auto& dropped = metrics["dropped"];
    EXPECT_EQ(dropped["too_short"].get<int>() + dropped["no_data"].get<int>() +
                  dropped["length_mismatch"].get<int>(),
              55);
    EXPECT_GT(dropped["too_short"].get<int>(), 0);
    EXPECT_GT(dropped["length_mismatch"].get<int>(), 5);
    EXPECT_EQ(metrics["accepted"], 1);
    for (const auto v : values_of("VALUE")) EXPECT_EQ(v, 1000);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
