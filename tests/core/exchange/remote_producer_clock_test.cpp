#include "eip2mqtt/core/exchange/remote_producer_clock.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using plan::TimestampSource;

// 2026-11-23 12:00:00 UTC, as a receive time; and a PLC clock that reads January 2000.
constexpr std::int64_t now_ms = 1795435200000;
constexpr std::uint32_t now_s = 1795435200;
constexpr std::uint32_t year_2000_s = 947817150;

TEST(RemoteProducerClock, AutoTakesTheProducersTimeWithinTheTolerance) {
    RemoteProducerClock clock(TimestampSource::automatic, 2000ms);
    EXPECT_EQ(clock.state(), ClockState::none);
    EXPECT_EQ(clock.on_datagram(now_s - 1, 500000000, now_ms), now_ms - 500);
    EXPECT_EQ(clock.state(), ClockState::synced);
    EXPECT_EQ(clock.offset_ms(), -500);
    EXPECT_EQ(clock.on_datagram(now_s + 2, 0, now_ms), now_ms + 2000);  // at the tolerance
    EXPECT_EQ(clock.state(), ClockState::synced);
}

TEST(RemoteProducerClock, AutoTakesTheReceiveTimeBeyondTheTolerance) {
    RemoteProducerClock clock(TimestampSource::automatic, 2000ms);
    EXPECT_EQ(clock.on_datagram(year_2000_s, 740000000, now_ms), now_ms);
    EXPECT_EQ(clock.state(), ClockState::unsynced);
    EXPECT_EQ(clock.offset_ms(), std::int64_t{year_2000_s} * 1000 + 740 - now_ms);
    EXPECT_EQ(clock.on_datagram(now_s + 2, 1000000, now_ms), now_ms);  // 2001 ms ahead
    EXPECT_EQ(clock.state(), ClockState::unsynced);
    // Synchronised again: the producer's time again.
    EXPECT_EQ(clock.on_datagram(now_s, 0, now_ms), now_ms);
    EXPECT_EQ(clock.on_datagram(now_s, 250000000, now_ms), now_ms + 250);
    EXPECT_EQ(clock.state(), ClockState::synced);
}

TEST(RemoteProducerClock, NoTimestampIsAlwaysTheReceiveTime) {
    for (const auto source :
         {TimestampSource::automatic, TimestampSource::producer, TimestampSource::receive}) {
        RemoteProducerClock clock(source, 2000ms);
        clock.on_datagram(now_s, 0, now_ms);
        EXPECT_EQ(clock.on_datagram(0, 0, now_ms + 7), now_ms + 7);
        EXPECT_EQ(clock.state(), ClockState::none);
        EXPECT_EQ(clock.offset_ms(), 0);  // the last stamped datagram's
    }
}

TEST(RemoteProducerClock, ProducerAndReceiveAreTakenWhateverTheClock) {
    RemoteProducerClock producer(TimestampSource::producer, 2000ms);
    EXPECT_EQ(producer.on_datagram(year_2000_s, 0, now_ms), std::int64_t{year_2000_s} * 1000);
    EXPECT_EQ(producer.state(), ClockState::unsynced);
    RemoteProducerClock receive(TimestampSource::receive, 2000ms);
    EXPECT_EQ(receive.on_datagram(now_s, 100000000, now_ms), now_ms);
    EXPECT_EQ(receive.state(), ClockState::synced);
}

TEST(RemoteProducerClock, StateNames) {
    EXPECT_EQ(to_string(ClockState::none), "none");
    EXPECT_EQ(to_string(ClockState::synced), "synced");
    EXPECT_EQ(to_string(ClockState::unsynced), "unsynced");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
