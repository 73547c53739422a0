// The write log of the status page: each write as it arrived, its result once given (a later
// one replacing it), newest first, the oldest going beyond the bound.

#include "eip2mqtt/app/exchanges/write_log.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "eip2mqtt/app/northbound/northbound.hpp"
#include "tests/app/support/test_plan.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using json = nlohmann::json;

class WriteLogTest : public ::testing::Test {
protected:
    WriteRequest accepted(std::int64_t value) const {
        return {{"acme/sp/VALUE/set/result", "", nullptr, WriteOrigin::mqtt},
                "acme/sp/VALUE/set",
                ExchangeWrite{&plan_, {{0, core::plan::Value{value}}}},
                {}};
    }
    json entries() const {
        std::string out;
        log_.append_json(out);
        return json::parse(out);
    }

    core::plan::ExchangePlan plan_ = test::test_produced_plan();
    core::WallTime t0_{std::chrono::seconds(1'700'000'000)};
    WriteLog log_;
};

TEST_F(WriteLogTest, AWriteShowsItsValuesThenItsResult) {
    const auto id = log_.arrived(accepted(5), t0_);
    WriteRequest refused{{"r", "", nullptr, WriteOrigin::commands},
                         "device 10.0.0.1/10",
                         core::write::WriteRejection{core::write::WriteError::unknown_tag, "x"},
                         {}};
    const auto other = log_.arrived(refused, t0_ + std::chrono::milliseconds(1));
    log_.answered(other, "unknown tag", t0_ + std::chrono::milliseconds(2));
    auto shown = entries();
    ASSERT_EQ(shown.size(), 2u);
    EXPECT_EQ(shown[0], json::parse(R"({"id":2,"time":1700000000001,"origin":"commands",
        "target":"device 10.0.0.1/10","values":"","result":"unknown tag",
        "answered_at":1700000000002})"));
    EXPECT_EQ(shown[1]["values"], "VALUE=5");
    EXPECT_TRUE(shown[1]["result"].is_null());
    log_.answered(id, "handed to the other unit", t0_);
    log_.answered(id, "ok", t0_ + std::chrono::seconds(1));  // settled on taking the lead
    EXPECT_EQ(entries()[1]["result"], "ok");
}

TEST_F(WriteLogTest, TheOldestGoesBeyondTheBoundAndItsResultFindsNothing) {
    const auto first = log_.arrived(accepted(0), t0_);
    for (int i = 1; i <= static_cast<int>(WriteLog::kept); ++i) log_.arrived(accepted(i), t0_);
    EXPECT_EQ(log_.size(), WriteLog::kept);
    log_.answered(first, "ok", t0_);
    const auto shown = entries();
    EXPECT_EQ(shown.front()["values"], "VALUE=100");
    EXPECT_EQ(shown.back()["values"], "VALUE=1");
    for (const auto& entry : shown) EXPECT_TRUE(entry["result"].is_null());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
