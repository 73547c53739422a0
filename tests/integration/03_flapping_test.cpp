// A producer whose datagrams alternate good and bad (a length fault) neither floods the broker
// nor the log: each tag's quality and the exchange's `_status` are republished at most once a
// period, the log has a summary, and what is published ends on the last datagram.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <utility>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

constexpr auto period = 200ms;

std::vector<std::byte> good(std::uint16_t rid, std::int64_t speed, std::int64_t level) {
    return DatagramBuilder("10.0.0.2", 7, 8)
        .request_id(rid)
        .set("0.0", TagType::dint, speed)
        .set("4.0", TagType::dint, level)
        .build();
}

class FlappingTest : public GatewayTest {
protected:
    std::size_t count_after(const std::string& suffix, std::size_t from) const {
        const auto all = recorder_->messages();
        return static_cast<std::size_t>(
            std::count_if(all.begin() + static_cast<std::ptrdiff_t>(from), all.end(),
                          [&](const Received& m) { return m.topic == topic(suffix); }));
    }

    // Whole periods and seconds begun since t0, each rounded up.
    static std::pair<std::size_t, std::size_t> periods_and_seconds_since(
        std::chrono::steady_clock::time_point t0) {
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - t0;
        const auto periods =
            static_cast<std::size_t>(std::ceil(elapsed / std::chrono::duration<double>(period)));
        return {periods, static_cast<std::size_t>(std::ceil(elapsed.count()))};
    }
};

TEST_F(FlappingTest, AlternatingGoodAndShortDatagramsArePublishedOncePerPeriodAndSummarised) {
    start(ExchangeYaml::consume("pump", "10.0.0.2", 7)
              .length(8)
              .period_ms(static_cast<std::uint32_t>(period.count()))
              .timeout_ms(0)
              .tag("SPEED", "0.0", "dint")
              .tag("LEVEL", "4.0", "dint")
              .str());
    std::uint16_t rid = 1;
    send(good(rid, 10, 20));
    expect_field(topic("pump/LEVEL"), "value", "20");
    const auto from = recorder_->count();
    const auto log_from = gateway_->output().size();

    // 200 datagrams, one every 10 ms or so (a busy machine stretches it, and the bound with it):
    // 20 a period, each published before the next comes while nothing paces them (sent in one
    // burst, the MQTT queue's newest-wins would hide the flood).
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 100; ++i) {
        auto short_one = good(++rid, 10, 20);
        short_one.resize(32 + 6);  // 6 data bytes of 8: a length mismatch
        send(short_one);
        std::this_thread::sleep_for(10ms);
        send(good(++rid, 10, 20));
        std::this_thread::sleep_for(10ms);
    }
    send(good(++rid, 11, 21));
    // The last values, good, and the status counting every datagram, in state ok.
    expect_field(topic("pump/SPEED"), "value", "11", from);
    expect_field(topic("pump/LEVEL"), "value", "21", from);
    const auto status = recorder_->wait_for_message(
        topic("pump/_status"),
        [](const std::string& p) {
            const auto j = json::parse(p);
            return j["received"] == 202 && j["state"] == "ok";
        },
        10s, from);
    ASSERT_TRUE(status.has_value());
    EXPECT_EQ(json::parse(recorder_->last(topic("pump/SPEED"))->payload)["quality"], "good");
    EXPECT_EQ(json::parse(recorder_->last(topic("pump/LEVEL"))->payload)["quality"], "good");

    // At most one report per period elapsed, plus the burst of two and the final values; the
    // status also once a second while its counters move. Before: about 200 of each. The
    // reports are counted first and the time after: every report counted was made inside
    // [t0, now], so a slow machine only widens the bound, never narrows it.
    const auto speed = count_after("pump/SPEED", from);
    const auto level = count_after("pump/LEVEL", from);
    const auto statuses = count_after("pump/_status", from);
    const auto [periods, seconds] = periods_and_seconds_since(t0);
    EXPECT_LE(speed, periods + 3) << periods << " periods";
    EXPECT_LE(level, periods + 3) << periods << " periods";
    EXPECT_LE(statuses, periods + seconds + 3) << periods << " periods";

    // The log: a few lines, then a summary; not a line per datagram.
    const auto log = gateway_->output().substr(log_from);
    const auto lines = static_cast<std::size_t>(std::count(log.begin(), log.end(), '\n'));
    EXPECT_LE(lines, 8u) << log;
    EXPECT_NE(log.find("too many to log each"), std::string::npos) << log;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
