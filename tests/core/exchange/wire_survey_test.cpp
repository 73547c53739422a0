// WireSurvey (`sniff --yaml`): what the wire shows of an unconfigured exchange,
// with injected receive times.

#include "eip2mqtt/core/exchange/wire_survey.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const wire::ExchangeKey key{wire::ProducerId{0x0A000009}, 3};
const Destination unicast{DestinationKind::unicast, 0x7F000001};
// 2023-09-20T17:41:18Z in ms.
constexpr std::int64_t receive_ms = 1695231678000;

wire::Header header(std::uint16_t rid, std::uint32_t time_s = 0, std::uint32_t time_ns = 0) {
    wire::Header h;
    h.producer_id = key.producer_id;
    h.exchange_id = key.exchange_id;
    h.request_id = rid;
    h.time_s = time_s;
    h.time_ns = time_ns;
    h.signature = 0x0102;  // 1.2
    return h;
}

const MonoTime t0 = MonoTime{} + 1h;

/// Feeds datagrams of `rids` arriving at `t0 + times`, 8 data bytes each, no timestamp.
WireSummary survey(const std::vector<std::uint16_t>& rids,
                   const std::vector<std::chrono::milliseconds>& times) {
    WireSurvey s(key);
    for (std::size_t i = 0; i < rids.size(); ++i) {
        s.on_datagram(header(rids[i]), 8, unicast, t0 + times[i], receive_ms + times[i].count());
    }
    return s.summary();
}

TEST(ClassifyDestination, MulticastBroadcastUnicastAndUnknown) {
    const std::array<std::uint32_t, 1> broadcasts{0x0A0000FF};  // 10.0.0.255
    EXPECT_EQ(classify_destination(0xE0000701, broadcasts),
              (Destination{DestinationKind::multicast, 0xE0000701}));  // 224.0.7.1
    EXPECT_EQ(classify_destination(0xEFFFFFFF, broadcasts).kind, DestinationKind::multicast);
    EXPECT_EQ(classify_destination(0xFFFFFFFF, broadcasts).kind, DestinationKind::broadcast);
    EXPECT_EQ(classify_destination(0x0A0000FF, broadcasts),
              (Destination{DestinationKind::broadcast, 0x0A0000FF}));
    // x.y.z.255 is a host address on a wider subnet: only the interfaces' say it is broadcast.
    EXPECT_EQ(classify_destination(0x0A0100FF, broadcasts).kind, DestinationKind::unicast);
    EXPECT_EQ(classify_destination(0x7F000001, broadcasts),
              (Destination{DestinationKind::unicast, 0x7F000001}));
    EXPECT_EQ(classify_destination(0xF0000001, broadcasts).kind, DestinationKind::unicast);
    EXPECT_EQ(classify_destination(0, broadcasts), Destination{});
    EXPECT_EQ(to_string(DestinationKind::multicast), "multicast");
}

TEST(WireSurvey, OneDatagramHasNoPeriod) {
    const auto s = survey({1}, {0ms});
    EXPECT_EQ(s.key, key);
    EXPECT_EQ(s.datagrams, 1u);
    EXPECT_EQ(s.length, 8);
    EXPECT_EQ(s.signature, (wire::Signature{1, 2}));
    EXPECT_FALSE(s.period_ms.has_value());
    EXPECT_EQ(s.period_steps, 0u);
    EXPECT_EQ(s.destination, unicast);
    EXPECT_EQ(s.clock, ClockState::none);
}

TEST(WireSurvey, PeriodIsTheMeanTimePerRequestIdStep) {
    const auto s = survey({1, 2, 3, 4}, {0ms, 20ms, 41ms, 60ms});
    ASSERT_TRUE(s.period_ms.has_value());
    EXPECT_DOUBLE_EQ(*s.period_ms, 20.0);
    EXPECT_EQ(s.period_steps, 3u);
}

TEST(WireSurvey, LostDatagramsStillCountAsPeriods) {
    // rid 3 and 4 lost: 5 is three periods after 2.
    const auto s = survey({1, 2, 5, 6}, {0ms, 20ms, 80ms, 100ms});
    EXPECT_DOUBLE_EQ(*s.period_ms, 20.0);
    EXPECT_EQ(s.period_steps, 5u);
}

TEST(WireSurvey, DuplicatesAndLateDatagramsCountForNothing) {
    // 2 twice; 3 arrives after 4.
    const auto s = survey({1, 2, 2, 4, 3, 5}, {0ms, 20ms, 21ms, 60ms, 61ms, 80ms});
    EXPECT_EQ(s.datagrams, 6u);
    EXPECT_DOUBLE_EQ(*s.period_ms, 20.0);
    EXPECT_EQ(s.period_steps, 4u);
}

TEST(WireSurvey, RequestIdsWrapAt65536) {
    const auto s = survey({65534, 65535, 0, 1}, {0ms, 10ms, 20ms, 30ms});
    EXPECT_DOUBLE_EQ(*s.period_ms, 10.0);
    EXPECT_EQ(s.period_steps, 3u);
}

TEST(WireSurvey, AProducerThatRestartsIsMeasuredOnFromItsNewRequestIds) {
    // 100, 101 at 20 ms; a silence; the producer restarts at 1 and sends every 20 ms again.
    const auto s = survey({100, 101, 1, 2, 3}, {0ms, 20ms, 5000ms, 5020ms, 5040ms});
    EXPECT_DOUBLE_EQ(*s.period_ms, 20.0);
    EXPECT_EQ(s.period_steps, 3u);
}

TEST(WireSurvey, ALengthThatVariesKeepsTheLastAndTheRange) {
    WireSurvey s(key);
    s.on_datagram(header(1), 10, unicast, t0, receive_ms);
    s.on_datagram(header(2), 8, unicast, t0 + 20ms, receive_ms + 20);
    s.on_datagram(header(3), 12, unicast, t0 + 40ms, receive_ms + 40);
    s.on_datagram(header(4), 10, unicast, t0 + 60ms, receive_ms + 60);
    EXPECT_EQ(s.summary().length, 10);
    EXPECT_EQ(s.summary().min_length, 8);
    EXPECT_EQ(s.summary().max_length, 12);
}

TEST(WireSurvey, SignatureAndDestinationThatVaryAreFlagged) {
    WireSurvey s(key);
    s.on_datagram(header(1), 8, unicast, t0, receive_ms);
    s.on_datagram(header(2), 8, unicast, t0 + 20ms, receive_ms + 20);
    EXPECT_FALSE(s.summary().signature_varied);
    EXPECT_FALSE(s.summary().destination_varied);
    auto h = header(3);
    h.signature = 0x0200;
    const Destination group{DestinationKind::multicast, 0xE0000701};
    s.on_datagram(h, 8, group, t0 + 40ms, receive_ms + 40);
    EXPECT_EQ(s.summary().signature, (wire::Signature{2, 0}));
    EXPECT_TRUE(s.summary().signature_varied);
    EXPECT_EQ(s.summary().destination, group);
    EXPECT_TRUE(s.summary().destination_varied);
}

TEST(WireSurvey, ClockIsSyncedWithin2000MsOfTheReceiveTimeUnsyncedBeyondNoneWithoutATimestamp) {
    WireSurvey s(key);
    // 1.5 s behind the receive time: synced.
    s.on_datagram(header(1, 1695231676, 500000000), 8, unicast, t0, receive_ms);
    EXPECT_EQ(s.summary().clock, ClockState::synced);
    EXPECT_EQ(s.summary().clock_offset_ms, -1500);
    EXPECT_EQ(s.summary().clock_tolerance, 2000ms);
    EXPECT_FALSE(s.summary().clock_varied);
    // 2.001 s ahead: unsynced.
    s.on_datagram(header(2, 1695231680, 21000000), 8, unicast, t0 + 20ms, receive_ms + 20);
    EXPECT_EQ(s.summary().clock, ClockState::unsynced);
    EXPECT_EQ(s.summary().clock_offset_ms, 2001);
    EXPECT_TRUE(s.summary().clock_varied);
    // No timestamp.
    s.on_datagram(header(3), 8, unicast, t0 + 40ms, receive_ms + 40);
    EXPECT_EQ(s.summary().clock, ClockState::none);
}

TEST(WireSurvey, ToleranceIsTheCallers) {
    WireSurvey s(key, 500ms);
    s.on_datagram(header(1, 1695231677, 0), 8, unicast, t0, receive_ms);  // 1 s behind
    EXPECT_EQ(s.summary().clock, ClockState::unsynced);
    EXPECT_EQ(s.summary().clock_tolerance, 500ms);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
