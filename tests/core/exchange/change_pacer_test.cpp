#include "eip2mqtt/core/exchange/change_pacer.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime t0 = MonoTime{} + 1h;

TEST(ChangePacer, AChangeAndItsReturnAreReportedAtOnce) {
    // A timeout, then the datagram that ends it 10 ms later.
    ChangePacer pacer(100ms);
    EXPECT_TRUE(pacer.on_change(t0));
    EXPECT_TRUE(pacer.on_change(t0 + 10ms));
    EXPECT_FALSE(pacer.holding());
    EXPECT_FALSE(pacer.next_due());
}

TEST(ChangePacer, ChangesAPeriodApartAreEachReportedAtOnce) {
    ChangePacer pacer(100ms);
    for (int i = 0; i < 20; ++i) EXPECT_TRUE(pacer.on_change(t0 + i * 100ms)) << i;
}

TEST(ChangePacer, AThirdChangeWithinAPeriodIsHeldUntilItsTime) {
    ChangePacer pacer(100ms);
    ASSERT_TRUE(pacer.on_change(t0));
    ASSERT_TRUE(pacer.on_change(t0 + 10ms));
    EXPECT_FALSE(pacer.on_change(t0 + 20ms));
    EXPECT_TRUE(pacer.holding());
    EXPECT_EQ(pacer.next_due(), t0 + 100ms);  // a period after the first: two per two periods
    EXPECT_FALSE(pacer.take_due(t0 + 99ms));
    EXPECT_TRUE(pacer.take_due(t0 + 100ms));
    EXPECT_FALSE(pacer.take_due(t0 + 101ms));  // once
    EXPECT_FALSE(pacer.holding());
    // The next one within a period of that is held in turn.
    EXPECT_FALSE(pacer.on_change(t0 + 150ms));
    EXPECT_EQ(pacer.next_due(), t0 + 200ms);
}

TEST(ChangePacer, AChangeThatRevertedBeforeItsTimeIsNotReported) {
    ChangePacer pacer(100ms);
    ASSERT_TRUE(pacer.on_change(t0));
    ASSERT_TRUE(pacer.on_change(t0 + 1ms));
    EXPECT_FALSE(pacer.on_change(t0 + 2ms));
    pacer.on_revert();
    EXPECT_FALSE(pacer.holding());
    EXPECT_FALSE(pacer.take_due(t0 + 500ms));
    // Quiet since: the next changes go at once.
    EXPECT_TRUE(pacer.on_change(t0 + 500ms));
    EXPECT_TRUE(pacer.on_change(t0 + 501ms));
}

TEST(ChangePacer, AnAlternatingStreamIsReportedAtMostOncePerPeriodPlusTheBurst) {
    // 2,000 changes, one every millisecond, over 2 s of a 100 ms exchange, with a tick each
    // millisecond: at most 2 s / 100 ms reports plus the burst, and still one each period.
    ChangePacer pacer(100ms);
    bool reported = true;  // good
    bool actual = true;
    int reports = 0;
    for (int ms = 0; ms < 2000; ++ms) {
        const auto now = t0 + std::chrono::milliseconds(ms);
        if (pacer.take_due(now)) {
            reported = actual;
            ++reports;
        }
        actual = !actual;  // the datagram of this millisecond
        if (actual == reported) {
            pacer.on_revert();
        } else if (pacer.on_change(now)) {
            reported = actual;
            ++reports;
        }
    }
    EXPECT_LE(reports, 20 + ChangePacer::burst);
    EXPECT_GE(reports, 10);
    // The last datagram was good (2,000 flips): what is reported ends on it once due.
    EXPECT_TRUE(actual);
    if (reported != actual) {
        EXPECT_TRUE(pacer.take_due(t0 + 2100ms));
    }
}

TEST(ChangePacer, AZeroPeriodHoldsNothing) {
    ChangePacer pacer(0ms);
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(pacer.on_change(t0));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
