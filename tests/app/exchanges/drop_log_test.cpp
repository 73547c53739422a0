#include "eip2mqtt/app/exchanges/drop_log.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/support/fakes/log_capture.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::wire::DropReason;

class DropLogTest : public ::testing::Test {
protected:
    std::vector<std::string> lines() { return log_.lines(); }

    test::LogCapture log_;
    const core::MonoTime t0{std::chrono::hours(1)};
};

TEST_F(DropLogTest, AFloodThatStopsIsSummarisedOnceTheIntervalHasPassed) {
    DropLog log(60s);
    log.record(DropReason::too_short, t0, "3 bytes from 10.0.0.1:1");
    EXPECT_EQ(lines(), std::vector<std::string>{"dropped datagram (too_short): 3 bytes from "
                                                "10.0.0.1:1"});
    for (int i = 1; i <= 5; ++i) log.record(DropReason::too_short, t0 + i * 1s, "later");
    // The flood stops: no drop will come to log its count. The tick does, once a minute has
    // passed since the first line, and only then.
    log.flush(t0 + 30s);
    log.flush(t0 + 59s);
    EXPECT_TRUE(lines().empty());
    log.flush(t0 + 60s);
    EXPECT_EQ(lines(),
              std::vector<std::string>{"dropped 5 datagrams (too_short) in the last 60 s"});
    // Said once.
    log.flush(t0 + 61s);
    log.flush(t0 + 10min);
    EXPECT_TRUE(lines().empty());
}

TEST_F(DropLogTest, AfterAFlushedSummaryTheIntervalStartsAgain) {
    DropLog log(60s);
    log.record(DropReason::duplicate, t0, "first");
    log.record(DropReason::duplicate, t0 + 1s, "second");
    log.flush(t0 + 60s);
    EXPECT_EQ(lines().size(), 2u);
    // A drop within the interval after the summary waits for the next one.
    log.record(DropReason::duplicate, t0 + 70s, "third");
    log.flush(t0 + 119s);
    EXPECT_TRUE(lines().empty());
    log.flush(t0 + 120s);
    EXPECT_EQ(lines(), std::vector<std::string>{"dropped 1 datagram (duplicate) in the last 60 s"});
    // A drop after a quiet interval is logged at once with its details, as the first was.
    log.record(DropReason::duplicate, t0 + 200s, "fourth");
    EXPECT_EQ(lines(), std::vector<std::string>{"dropped datagram (duplicate): fourth"});
}

TEST_F(DropLogTest, ANextDropStillCarriesTheSummaryWithItsDetail) {
    DropLog log(60s);
    log.record(DropReason::no_data, t0, "first");
    log.record(DropReason::no_data, t0 + 1s, "second");
    log.record(DropReason::no_data, t0 + 61s, "third");
    EXPECT_EQ(lines().back(), "dropped 2 datagrams (no_data) in the last 60 s; latest: third");
    log.flush(t0 + 200s);  // nothing left to summarise
    EXPECT_TRUE(lines().empty());
}

TEST_F(DropLogTest, ReasonsAreSummarisedEachOnItsOwnInterval) {
    DropLog log(60s);
    log.record(DropReason::too_short, t0, "a");
    log.record(DropReason::too_short, t0 + 1s, "a");
    log.record(DropReason::out_of_order, t0 + 30s, "b");
    log.record(DropReason::out_of_order, t0 + 31s, "b");
    log.record(DropReason::out_of_order, t0 + 32s, "b");
    lines();
    log.flush(t0 + 60s);
    EXPECT_EQ(lines(), std::vector<std::string>{"dropped 1 datagram (too_short) in the last 60 s"});
    log.flush(t0 + 90s);
    EXPECT_EQ(lines(),
              std::vector<std::string>{"dropped 2 datagrams (out_of_order) in the last 60 s"});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
