// Every northbound's writes in one place: a decoded write is staged or refused; each
// refusal is counted under its error and answered through the northbound it came from. Time is
// injected.

#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/log_capture.hpp"
#include "tests/support/fakes/recording_northbound.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using core::write::WriteError;
using core::write::WriteRejection;

class WriteDispatcherTest : public ::testing::Test {
protected:
    WriteRequest request(std::variant<ExchangeWrite, WriteRejection> outcome) {
        return {{"reply/topic", "id", &origin_}, "acme/t1/out/set", std::move(outcome), {}};
    }
    std::uint64_t rejected(WriteError error) const {
        return dispatcher_.counters().writes_rejected[static_cast<std::size_t>(error)];
    }

    test::RecordingNorthbound origin_;
    core::plan::ExchangePlan plan_;       ///< the produced exchange written to
    std::vector<ProducerHandle> staged_;  ///< the producer of each staged write
    std::optional<WriteRejection> exchange_refuses_;
    test::FakeClock clock_;
    /// Where refusals are answered, as in the gateway: the fan-out, which hands each to its
    /// origin.
    northbound::FanOut results_;
    WriteDispatcher dispatcher_{[this](ExchangeWrite&& write, const WriteReply& reply,
                                       core::MonoTime now) -> std::optional<WriteRejection> {
                                    EXPECT_EQ(reply.topic, "reply/topic");
                                    EXPECT_EQ(now, clock_.monotonic());
                                    if (exchange_refuses_) return exchange_refuses_;
                                    staged_.push_back(write.producer);
                                    return std::nullopt;
                                },
                                results_, clock_};
};

TEST_F(WriteDispatcherTest, AnAcceptedWriteIsStagedOnItsExchangeAndCountedNotAnswered) {
    dispatcher_.on_write(request(ExchangeWrite{&plan_, {{0, core::plan::Value{true}}}}));
    EXPECT_EQ(staged_, std::vector<ProducerHandle>{&plan_});
    EXPECT_EQ(dispatcher_.counters().writes_ok, 1u);
    EXPECT_TRUE(origin_.results.empty());  // answered once its datagram is sent
}

TEST_F(WriteDispatcherTest, AcceptedWritesAreCountedByTheProtocolTheyCameBy) {
    auto by_command = request(ExchangeWrite{&plan_, {{0, core::plan::Value{true}}}});
    by_command.reply.via = WriteOrigin::commands;
    dispatcher_.on_write(std::move(by_command));
    dispatcher_.on_write(request(ExchangeWrite{&plan_, {{0, core::plan::Value{true}}}}));
    auto refused = request(WriteRejection{WriteError::read_only, "read-only"});
    refused.reply.via = WriteOrigin::commands;
    dispatcher_.on_write(std::move(refused));
    const auto& by_origin = dispatcher_.counters().writes_by_origin;
    EXPECT_EQ(by_origin[static_cast<std::size_t>(WriteOrigin::commands)], 1u);
    EXPECT_EQ(by_origin[static_cast<std::size_t>(WriteOrigin::mqtt)], 1u);
    EXPECT_EQ(by_origin[static_cast<std::size_t>(WriteOrigin::sparkplug)], 0u);
}

TEST_F(WriteDispatcherTest, ARefusalPassesTheFanOutWhichNotesItsReasonInTheWriteLog) {
    results_.set_write_log(dispatcher_.write_log(), clock_);
    dispatcher_.on_write(request(WriteRejection{WriteError::read_only, "read-only"}));
    std::string logged;
    dispatcher_.write_log().append_json(logged);
    EXPECT_NE(logged.find(R"("target":"acme/t1/out/set")"), std::string::npos) << logged;
    EXPECT_NE(logged.find(R"("result":"read-only")"), std::string::npos) << logged;
    ASSERT_EQ(origin_.results.size(), 1u);  // and answered by its origin, once
}

TEST_F(WriteDispatcherTest, ARefusalIsCountedUnderItsErrorAndAnsweredByItsOrigin) {
    dispatcher_.on_write(request(WriteRejection{WriteError::read_only, "read-only"}));
    EXPECT_TRUE(staged_.empty());
    EXPECT_EQ(rejected(WriteError::read_only), 1u);
    ASSERT_EQ(origin_.results.size(), 1u);
    EXPECT_EQ(origin_.results[0].topic, "reply/topic");
    EXPECT_EQ(origin_.results[0].error, "read-only");
}

TEST_F(WriteDispatcherTest, TheLogLineCarriesTheRefusalWhole) {
    // A retained write's refusal says how to clear it (WriteRouterTest); the operator reads
    // that in the log as well as in the result.
    test::LogCapture log;
    const std::string advice =
        "retained writes are refused; publish without retain, and clear the retained one with "
        "`mosquitto_pub -r -n -t 'acme/t1/out/set'`";
    dispatcher_.on_write(request(WriteRejection{WriteError::retained, advice}));
    const auto lines = log.lines();
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("write to acme/t1/out/set rejected: " + advice), std::string::npos)
        << lines[0];
}

TEST_F(WriteDispatcherTest, WhatTheExchangeRefusesIsCountedAndAnsweredTheSameWay) {
    exchange_refuses_ = WriteRejection{WriteError::queue_full, "full"};
    dispatcher_.on_write(request(ExchangeWrite{&plan_, {}}));
    EXPECT_EQ(dispatcher_.counters().writes_ok, 0u);
    EXPECT_EQ(rejected(WriteError::queue_full), 1u);
    ASSERT_EQ(origin_.results.size(), 1u);
    EXPECT_EQ(origin_.results[0].error, "full");
}

TEST_F(WriteDispatcherTest, AWriteWithNobodyToAnswerIsStillCounted) {
    auto orphan = request(WriteRejection{WriteError::unknown_tag, "unknown tag"});
    orphan.reply.origin = nullptr;
    dispatcher_.on_write(std::move(orphan));
    EXPECT_EQ(rejected(WriteError::unknown_tag), 1u);
    EXPECT_TRUE(origin_.results.empty());
}

TEST_F(WriteDispatcherTest, ReloadCancellationsAreCounted) {
    dispatcher_.count_cancelled(4);
    EXPECT_EQ(dispatcher_.counters().writes_cancelled, 4u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
