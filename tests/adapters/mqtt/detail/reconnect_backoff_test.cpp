#include "adapters/mqtt/detail/reconnect_backoff.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using Clock = ReconnectBackoff::Clock;
using std::chrono::milliseconds;

constexpr milliseconds min_backoff = 250ms;
constexpr milliseconds max_backoff = 30s;

/// The times of the attempts made during an outage that starts at `start`, each failing at
/// once (a refused connection), until `until`.
std::vector<Clock::time_point> attempts(ReconnectBackoff& backoff, Clock::time_point start,
                                        Clock::duration until) {
    std::vector<Clock::time_point> times;
    auto now = start;
    while (now - start <= until) {
        now += backoff.next(now);
        times.push_back(now);
    }
    return times;
}

/// How long after `back` (the broker's return, counted from `start`) the first attempt comes.
Clock::duration found_after(const std::vector<Clock::time_point>& times, Clock::time_point start,
                            Clock::duration back) {
    for (const auto t : times) {
        if (t >= start + back) return t - (start + back);
    }
    ADD_FAILURE() << "no attempt after the broker came back";
    return Clock::duration::max();
}

TEST(ReconnectBackoff, AShortOutageIsFoundWithinAQuarterOfItsLength) {
    ReconnectBackoff backoff(min_backoff, max_backoff);
    const Clock::time_point start{};
    const auto times = attempts(backoff, start, 20s);
    // The broker comes back at any moment of the first 10 s: it is found within a quarter of
    // the outage (at least min_backoff). Plain doubling had reached 8 s by then.
    for (auto back = Clock::duration(0ms); back <= 10s; back += 10ms) {
        EXPECT_LE(found_after(times, start, back), std::max<Clock::duration>(min_backoff, back / 4))
            << "broker back after " << std::chrono::duration_cast<milliseconds>(back).count()
            << " ms";
    }
    EXPECT_LE(found_after(times, start, 10s), 2500ms);
}

TEST(ReconnectBackoff, ALongOutageIsTriedEveryMaxBackoff) {
    ReconnectBackoff backoff(min_backoff, max_backoff);
    const Clock::time_point start{};
    auto now = start;
    std::size_t count = 0;
    milliseconds delay{};
    while (now - start < 1h) {
        delay = backoff.next(now);
        EXPECT_LE(delay, max_backoff);
        EXPECT_GE(delay, min_backoff);
        if (now - start >= 2min) {
            EXPECT_EQ(delay, max_backoff);
        }
        now += delay;
        ++count;
    }
    EXPECT_EQ(delay, max_backoff);
    // About one attempt per 30 s once past two minutes, and a few dozen before: never a storm.
    EXPECT_LT(count, 3600 / 30 + 40);
}

TEST(ReconnectBackoff, StillDoublesWhenAttemptsTakeLong) {
    // Attempts that fail only after Paho's 30-s connect timeout age the outage quickly: the
    // delay is then the plain exponential one, below the age's cap.
    ReconnectBackoff backoff(min_backoff, max_backoff);
    Clock::time_point now{};
    std::vector<milliseconds> delays;
    for (int i = 0; i < 9; ++i) {
        delays.push_back(backoff.next(now));
        now += delays.back() + 30s;
    }
    const std::vector<milliseconds> expected = {250ms,  500ms,   1000ms,  2000ms, 4000ms,
                                                8000ms, 16000ms, 30000ms, 30000ms};
    EXPECT_EQ(delays, expected);
}

TEST(ReconnectBackoff, ResetStartsTheNextOutageFromMinBackoff) {
    ReconnectBackoff backoff(min_backoff, max_backoff);
    Clock::time_point now{};
    for (int i = 0; i < 200; ++i) now += backoff.next(now);
    EXPECT_EQ(backoff.next(now), max_backoff);
    backoff.reset();  // connected
    now += 1h;
    // A new outage: young again, so its first attempts come every min_backoff.
    EXPECT_EQ(backoff.next(now), min_backoff);
    now += min_backoff;
    EXPECT_EQ(backoff.next(now), min_backoff);
}

TEST(ReconnectBackoff, AMinAboveTheMaxIsTheDelay) {
    ReconnectBackoff backoff(500ms, 100ms);
    Clock::time_point now{};
    for (int i = 0; i < 10; ++i) {
        EXPECT_EQ(backoff.next(now), 500ms);
        now += 1min;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
